# attempts: operator.attrgetter('__globals__')(get_point_in_env) (np.ma.core.operator), then that module's __builtins__ dict's open()
# effect: file
# step: a provided function's globals
g = np.ma.core.operator.attrgetter('__globals__')(get_point_in_env)
bi = g['__builtins__']
opener = bi['open'] if isinstance(bi, dict) else bi.open
f = opener('@@MARKER_DIR@@/escaped_globals_builtins', 'w')
f.write('escaped through get_point_in_env.__globals__')
f.close()
