# attempts: os.kill(os.getpid(), SIGKILL): the process running the plan dies mid-step
# effect: signal
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.kill(osm.getpid(), 9)
