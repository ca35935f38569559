# attempts: mmap the canary read-write and change bytes in place (no write() call at all)
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
mmap = imp('mmap')
fd = osm.open('@@MARKER_DIR@@/../canary.txt', osm.O_RDWR)
m = mmap.mmap(fd, 0)
m[0:4] = b'XXXX'
m.flush()
m.close()
