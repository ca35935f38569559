# attempts: socket.create_connection to the loopback listener, socket from the real __import__
# effect: socket
# step: connect
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
s = imp('socket').create_connection(('127.0.0.1', @@PORT@@), timeout=5)
s.sendall(b'hello from plan code')
s.close()
