# attempts: raw syscalls socket(41)/connect(42) via ctypes.CDLL(None).syscall
# effect: socket
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
ctypes = imp('ctypes')
struct = imp('struct')
libc = ctypes.CDLL(None)
fd = libc.syscall(41, 2, 1, 0)
addr = struct.pack('=H', 2) + struct.pack('!H4s8x', @@PORT@@, bytes([127, 0, 0, 1]))
libc.syscall(42, fd, addr, len(addr))
libc.syscall(3, fd)
