# attempts: time.sleep(10**6) (blocked in C, no bytecode runs)
# effect: hang
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
imp('time').sleep(10**6)
