# attempts: shutil.copy the canary into the marker dir
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
imp('shutil').copy('@@MARKER_DIR@@/../canary.txt', '@@MARKER_DIR@@/canary_copy')
