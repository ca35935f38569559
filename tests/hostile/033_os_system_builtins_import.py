# attempts: os.system('touch ...') with os from the real __import__ (bltns route)
# effect: exec
# step: run a shell command
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.system('touch @@MARKER_DIR@@/os_system')
