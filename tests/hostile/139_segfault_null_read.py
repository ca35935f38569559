# attempts: ctypes.string_at(8): a near-NULL read kills the process with SIGSEGV
# effect: other
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
imp('ctypes').string_at(8, 16)
