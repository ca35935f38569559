# attempts: os.execv replaces the whole process with /bin/sh (whatever runs the plan is gone)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.execv('/bin/sh', ['sh', '-c', 'touch @@MARKER_DIR@@/execv_replaced; exit 0'])
