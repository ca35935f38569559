# attempts: os.kill(<harness pid>, SIGUSR1)
# effect: signal
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.kill(@@HARNESS_PID@@, 10)
