# attempts: libc getenv through ctypes (the C environment, whatever os.environ says)
# effect: env
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
ctypes = imp('ctypes')
libc = ctypes.CDLL(None)
libc.getenv.restype = ctypes.c_char_p
for k in (b'OPENAI_API_KEY', b'HGEN_TEST_SECRET'):
    v = libc.getenv(k) or b''
    print(k, v, v[::-1], v.hex())
