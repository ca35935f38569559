# attempts: os.fork() five times; each child writes a marker and _exits
# effect: fork
# step: fork
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
for i in range(5):
    pid = osm.fork()
    if pid == 0:
        fd = osm.open('@@MARKER_DIR@@/fork_child_' + str(i), osm.O_WRONLY | osm.O_CREAT, 0o644)
        osm._exit(0)
    osm.waitpid(pid, 0)
