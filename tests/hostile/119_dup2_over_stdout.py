# attempts: os.dup2 a marker file over fd 1, write 20 MB to fd 1
# effect: output
# step: hijack fd 1
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
fd = osm.open('@@MARKER_DIR@@/dup2_stdout', osm.O_WRONLY | osm.O_CREAT, 0o644)
osm.dup2(fd, 1)
osm.write(1, b'F' * 20_000_000)
