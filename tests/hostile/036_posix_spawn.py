# attempts: os.posix_spawn and os.spawnv (no shell, vfork/clone paths)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
pid = osm.posix_spawn('/usr/bin/touch', ['touch', '@@MARKER_DIR@@/posix_spawn'], {})
osm.waitpid(pid, 0)
osm.spawnv(osm.P_WAIT, '/usr/bin/touch', ['touch', '@@MARKER_DIR@@/spawnv'])
