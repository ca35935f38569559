# attempts: np.save (a blocked attribute name) fetched with operator.attrgetter('save')
# effect: file
# step: numpy file I/O
save = np.ma.core.operator.attrgetter('save')(np)
save('@@MARKER_DIR@@/np_save.npy', np.arange(4))
