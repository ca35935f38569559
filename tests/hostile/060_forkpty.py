# attempts: os.forkpty (pty + fork)
# effect: fork
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
pid, fd = osm.forkpty()
if pid == 0:
    osm.close(osm.open('@@MARKER_DIR@@/forkpty_child', osm.O_WRONLY | osm.O_CREAT, 0o644))
    osm._exit(0)
osm.waitpid(pid, 0)
