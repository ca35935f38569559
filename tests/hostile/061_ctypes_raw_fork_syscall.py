# attempts: raw syscall(SYS_fork=57) via ctypes, the child opens a marker with os.open
# effect: fork
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
libc = imp('ctypes').CDLL(None)
pid = libc.syscall(57)
if pid == 0:
    osm.close(osm.open('@@MARKER_DIR@@/raw_fork_child', osm.O_WRONLY | osm.O_CREAT, 0o644))
    osm._exit(0)
if pid > 0:
    osm.waitpid(pid, 0)
