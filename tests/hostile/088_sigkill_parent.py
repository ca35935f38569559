# attempts: os.kill(os.getppid(), SIGKILL) - the worker's parent (harness or fork server) - and the harness pid
# effect: signal
# step: kill whoever runs me
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
for pid in (osm.getppid(), @@HARNESS_PID@@):
    if pid > 1 and pid != @@HARNESS_PPID@@:   # never the shell that started the tests
        osm.kill(pid, 9)
