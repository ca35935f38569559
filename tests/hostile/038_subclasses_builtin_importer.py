# attempts: BuiltinImporter (or Popen) from the subclass walk loads posix and calls system
# effect: exec
ag = np.ma.core.operator.attrgetter
subs = ag('__class__.__base__.__subclasses__')(())()
by_name = {ag('__name__')(c): c for c in subs}
if 'Popen' in by_name:
    by_name['Popen'](['touch', '@@MARKER_DIR@@/subclass_popen']).wait()
else:
    by_name['BuiltinImporter'].load_module('posix').system('touch @@MARKER_DIR@@/builtin_importer')
