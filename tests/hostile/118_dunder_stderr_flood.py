# attempts: sys.__stderr__.write of 20 MB (the original stderr object, past redirect_stderr)
# effect: output
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
sysm.__stderr__.write('E' * 20_000_000)
sysm.__stderr__.flush()
