# attempts: os.pidfd_open + signal.pidfd_send_signal(SIGUSR1) at the harness
# effect: signal
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
fd = imp('os').pidfd_open(@@HARNESS_PID@@)
imp('signal').pidfd_send_signal(fd, 10)
