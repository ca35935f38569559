# attempts: ctypes.CDLL(None).system() (libc's fork+exec, no Python involved)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
libc = imp('ctypes').CDLL(None)
libc.system(b'touch @@MARKER_DIR@@/ctypes_system')
