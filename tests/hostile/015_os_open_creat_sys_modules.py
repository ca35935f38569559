# attempts: os.open(O_CREAT) with os from sys.modules, sys from np.ma.core.warnings' globals
# effect: file
# step: low-level open
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
osm = sysm.modules['os']
fd = osm.open('@@MARKER_DIR@@/os_open', osm.O_WRONLY | osm.O_CREAT, 0o644)
osm.write(fd, b'escaped via os.open')
osm.close(fd)
