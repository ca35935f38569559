# attempts: numpy's DataSource opens an http:// URL (urllib inside numpy), destpath in the marker dir
# effect: socket
DS = np.ma.core.operator.attrgetter('lib.npyio.DataSource')(np)
ds = DS('@@MARKER_DIR@@')
ds.open('http://127.0.0.1:@@PORT@@/data.txt')
