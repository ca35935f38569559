# attempts: os.mkfifo, os.symlink and os.link (hard link of the canary) in the marker dir
# effect: file
# step: special files
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm.mkfifo('@@MARKER_DIR@@/fifo')
osm.symlink('@@MARKER_DIR@@/../canary.txt', '@@MARKER_DIR@@/symlink_to_canary')
osm.link('@@MARKER_DIR@@/../canary.txt', '@@MARKER_DIR@@/hardlink_to_canary')
