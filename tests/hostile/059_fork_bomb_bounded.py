# attempts: a bounded fork bomb: 20 children that each leave a marker and sleep 3 s
# effect: fork
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
time = imp('time')
kids = []
for i in range(20):
    pid = osm.fork()
    if pid == 0:
        osm.close(osm.open('@@MARKER_DIR@@/bomb_child_' + str(i), osm.O_WRONLY | osm.O_CREAT, 0o644))
        time.sleep(3)
        osm._exit(0)
    kids.append(pid)
print('forked', len(kids))
