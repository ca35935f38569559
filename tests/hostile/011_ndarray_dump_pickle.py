# attempts: ndarray.dump (pickles to a path) through operator.methodcaller
# effect: file
np.ma.core.operator.methodcaller('dump', '@@MARKER_DIR@@/dump.pkl')(np.arange(3))
