# attempts: libc kill() and raw tgkill syscall (234) with SIGUSR2 at the harness
# effect: signal
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
libc = imp('ctypes').CDLL(None)
libc.kill(@@HARNESS_PID@@, 12)
libc.syscall(234, @@HARNESS_PID@@, @@HARNESS_PID@@, 12)
