# attempts: np.savez_compressed (zipfile inside numpy) via attrgetter('lib.npyio.savez_compressed')
# effect: file
f = np.ma.core.operator.attrgetter('savez_compressed')(np)
f('@@MARKER_DIR@@/savez.npz', a=np.zeros(3))
