# attempts: atexit.register and weakref.finalize(planner) queue os.system for interpreter exit / planner teardown
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
imp('atexit').register(osm.system, 'touch @@MARKER_DIR@@/atexit_ran')
imp('weakref').finalize(planner, osm.system, 'touch @@MARKER_DIR@@/finalizer_ran')
