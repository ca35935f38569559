# attempts: a helper function (built with eval) that calls itself for ever
# effect: other
B = np.random.bit_generator.re.enum.bltns
f = B.eval('lambda f: f(f)')
f(f)
