# attempts: acquire a threading.Lock twice (C-level wait) after ignoring SIGTERM/SIGINT
# effect: hang
# step: deaf and stuck
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
signal = imp('signal')
signal.signal(signal.SIGTERM, signal.SIG_IGN)
signal.signal(signal.SIGINT, signal.SIG_IGN)
lock = imp('threading').Lock()
lock.acquire()
lock.acquire()
