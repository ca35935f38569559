# attempts: a non-daemon thread sleeping for ever: the interpreter running the plan cannot exit
# effect: hang
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
t = imp('threading').Thread(target=imp('time').sleep, args=(10**6,), daemon=False)
t.start()
