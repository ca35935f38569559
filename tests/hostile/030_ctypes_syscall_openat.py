# attempts: libc open() through ctypes, and a raw syscall(SYS_openat) through ctypes.CDLL(None).syscall
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
ctypes = imp('ctypes')
libc = ctypes.CDLL(None, use_errno=True)
fd = libc.open(b'@@MARKER_DIR@@/libc_open', 0o1 | 0o100, 0o644)                  # libc open(O_WRONLY|O_CREAT)
libc.write(fd, b'libc open', 9)
fd = libc.syscall(257, -100, b'@@MARKER_DIR@@/raw_openat', 0o1 | 0o100, 0o644)   # openat(AT_FDCWD, ...)
libc.syscall(1, fd, b'raw syscall', 11)                                          # write
