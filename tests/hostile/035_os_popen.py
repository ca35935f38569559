# attempts: os.popen (a shell through subprocess) with os reached via sys.modules
# effect: exec
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
print(sysm.modules['os'].popen('touch @@MARKER_DIR@@/os_popen; echo done').read())
