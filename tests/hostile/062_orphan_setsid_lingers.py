# attempts: fork, setsid, and exec a shell that outlives the episode (its command line names the marker dir)
# effect: fork
# step: leave something running
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
pid = osm.fork()
if pid == 0:
    osm.setsid()
    osm.execv('/bin/sh', ['sh', '-c', 'sleep 6; touch @@MARKER_DIR@@/orphan_late', '@@MARKER_DIR@@'])
print('left', pid)
