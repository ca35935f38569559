# attempts: np.lib.format.open_memmap(mode='w+') through attrgetter('lib.format.open_memmap')
# effect: file
om = np.ma.core.operator.attrgetter('lib.format.open_memmap')(np)
a = om('@@MARKER_DIR@@/open_memmap.npy', mode='w+', dtype='float64', shape=(4,))
a[:] = 1.0
a.flush()
