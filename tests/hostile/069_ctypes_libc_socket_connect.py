# attempts: libc socket()/connect() through ctypes with a hand-built sockaddr_in
# effect: socket
# step: sockets without the socket module
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
ctypes = imp('ctypes')
struct = imp('struct')
libc = ctypes.CDLL(None)
fd = libc.socket(2, 1, 0)
addr = struct.pack('!HH4s8x', 0, @@PORT@@, bytes([127, 0, 0, 1]))
addr = struct.pack('=H', 2) + addr[2:]
libc.connect(fd, addr, len(addr))
libc.close(fd)
