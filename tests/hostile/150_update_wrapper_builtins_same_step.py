# attempts: the same copy of arrayprint's __globals__ and, in the same step, the real builtins it brought (`open` for writing in a function defined after the copy, `open` bound only in a branch never taken); the attribute name built from pieces at run time
# effect: file
# step: copy globals and use them at once
u = '_' * 2
def g():
    pass
np.core.arrayprint.contextlib.wraps(np.core.arrayprint.get_printoptions, assigned=(), updated=(u + 'globals' + u,))(g)
def f():
    return open('@@MARKER_DIR@@/update_wrapper', 'w').write('x')
if len(u) > 5:
    open = None
f()
