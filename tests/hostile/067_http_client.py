# attempts: http.client.HTTPConnection request, inside builtins.exec
# effect: socket
B = np.random.bit_generator.re.enum.bltns
B.exec('''
import http.client
c = http.client.HTTPConnection('127.0.0.1', @@PORT@@, timeout=5)
try:
    c.request('GET', '/')
except Exception:
    pass
''', {})
