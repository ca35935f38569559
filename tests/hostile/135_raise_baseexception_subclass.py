# attempts: raise a home-made BaseException subclass whose __str__ and __repr__ raise
# effect: other
B = np.random.bit_generator.re.enum.bltns
Boom = B.type('Boom', (B.BaseException,), {'__str__': B.eval('lambda self: 1/0'), '__repr__': B.eval('lambda self: 1/0')})
raise Boom()
