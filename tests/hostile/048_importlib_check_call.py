# attempts: importlib.import_module('subprocess').check_call, importlib taken from sys.modules
# effect: exec
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
il = sysm.modules['importlib']
il.import_module('subprocess').check_call(['/bin/sh', '-c', 'touch @@MARKER_DIR@@/importlib_check_call'])
