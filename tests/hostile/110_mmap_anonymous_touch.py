# attempts: anonymous mmap of 32 GiB, every page touched through np.frombuffer
# effect: memory
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
mmap = imp('mmap')
m = mmap.mmap(-1, 32 * 2**30)
v = np.frombuffer(m, dtype=np.uint8)
v[::4096] = 1
