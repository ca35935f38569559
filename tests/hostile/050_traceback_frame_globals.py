# attempts: exec'd try/except: e.__traceback__.tb_frame.f_back chain to a module with os; exec via the __builtins__ dict of a function's globals
# effect: exec
bi = np.ma.core.operator.attrgetter('__globals__')(get_point_in_env)['__builtins__']
bi['exec']('''
try:
    1 / 0
except ZeroDivisionError as e:
    f = e.__traceback__.tb_frame
while f is not None:
    if 'os' in f.f_globals and hasattr(f.f_globals['os'], 'system'):
        f.f_globals['os'].system('touch @@MARKER_DIR@@/traceback_frames')
        break
    f = f.f_back
else:
    __import__('os').system('touch @@MARKER_DIR@@/traceback_fallback')
''', {'__builtins__': bi})
