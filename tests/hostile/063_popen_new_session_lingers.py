# attempts: subprocess.Popen(start_new_session=True) of a sleeping shell, never waited for
# effect: fork
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
sp = imp('subprocess')
p = sp.Popen(['/bin/sh', '-c', 'sleep 6; touch @@MARKER_DIR@@/popen_late', '@@MARKER_DIR@@'], start_new_session=True)
print(p.pid)
