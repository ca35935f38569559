# attempts: os.fork, then ctypes libc.execve of /bin/sh in the child
# effect: exec
# step: fork then execve through libc
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
ctypes = imp('ctypes')
libc = ctypes.CDLL(None)
argv = (ctypes.c_char_p * 4)(b'/bin/sh', b'-c', b'touch @@MARKER_DIR@@/ctypes_execve', None)
envp = (ctypes.c_char_p * 1)(None)
pid = osm.fork()
if pid == 0:
    libc.execve(b'/bin/sh', argv, envp)
    osm._exit(3)
osm.waitpid(pid, 0)
