# attempts: shelve.open (dbm) and sqlite3.connect (C-level open) create databases
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
db = imp('sqlite3').connect('@@MARKER_DIR@@/escaped.sqlite')
db.execute('create table t (x)')
db.commit()
db.close()
s = imp('shelve').open('@@MARKER_DIR@@/escaped_shelf')
s['k'] = 1
s.close()
