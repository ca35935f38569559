# attempts: pickle.loads of an object whose __reduce__ returns (os.system, cmd)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
pickle = imp('pickle')
Evil = B.type('Evil', (), {'__reduce__': B.eval("lambda self: (system, ('touch @@MARKER_DIR@@/pickle_reduce',))", {'system': osm.system})})
pickle.loads(pickle.dumps(Evil()))
