# attempts: tempfile.mkstemp / NamedTemporaryFile(delete=False) in the marker directory
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
tf = imp('tempfile')
fd, path = tf.mkstemp(dir='@@MARKER_DIR@@', prefix='mkstemp_')
f = tf.NamedTemporaryFile(dir='@@MARKER_DIR@@', prefix='ntf_', delete=False)
f.write(b'x')
f.close()
