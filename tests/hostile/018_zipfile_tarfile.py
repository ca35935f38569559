# attempts: zipfile.ZipFile(w) and tarfile.open(w) create archives
# effect: file
# step: archives
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
z = imp('zipfile').ZipFile('@@MARKER_DIR@@/out.zip', 'w')
z.writestr('a.txt', 'escaped')
z.close()
t = imp('tarfile').open('@@MARKER_DIR@@/out.tar', 'w')
t.close()
