# attempts: os.rename the canary into the marker dir
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.rename('@@MARKER_DIR@@/../canary.txt', '@@MARKER_DIR@@/renamed_canary')
