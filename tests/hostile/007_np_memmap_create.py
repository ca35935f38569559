# attempts: np.memmap(mode='w+') creates and writes a file
# effect: file
# step: memory-mapped file
memmap = np.ma.core.operator.attrgetter('memmap')(np)
mm = memmap('@@MARKER_DIR@@/memmap.bin', dtype='uint8', mode='w+', shape=(64,))
mm[:] = 7
mm.flush()
