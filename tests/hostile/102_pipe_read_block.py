# attempts: os.read on an empty pipe nobody writes to (a C-level wait)
# effect: hang
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
r, w = osm.pipe()
osm.read(r, 1)
