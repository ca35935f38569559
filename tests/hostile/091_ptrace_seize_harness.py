# attempts: ptrace(PTRACE_SEIZE) the harness (no stop), write a marker if it worked, then PTRACE_DETACH
# effect: signal
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
libc = imp('ctypes').CDLL(None, use_errno=True)
r = libc.ptrace(0x4206, @@HARNESS_PID@@, None, None)
if r == 0:
    libc.ptrace(17, @@HARNESS_PID@@, None, None)
    f = B.open('@@MARKER_DIR@@/ptrace_seized', 'w')
    f.close()
    raise RuntimeError('ptrace seize of the harness succeeded')
