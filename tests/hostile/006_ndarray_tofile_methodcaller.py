# attempts: ndarray.tofile through operator.methodcaller
# effect: file
np.ma.core.operator.methodcaller('tofile', '@@MARKER_DIR@@/tofile.bin')(np.arange(8.0))
