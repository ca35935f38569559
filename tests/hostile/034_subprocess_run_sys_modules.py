# attempts: subprocess.run from sys.modules (or importlib) with sys from warnings' globals
# effect: exec
# step: subprocess
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
sp = sysm.modules.get('subprocess') or sysm.modules['importlib'].import_module('subprocess')
sp.run(['touch', '@@MARKER_DIR@@/subprocess_run'], check=False)
