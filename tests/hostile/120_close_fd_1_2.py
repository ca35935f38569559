# attempts: os.close(1) and os.close(2) (and dup2 /dev/null over them) so nothing can be reported
# effect: output
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
null = osm.open('/dev/null', osm.O_WRONLY)
osm.dup2(null, 2)
osm.close(1)
print('after closing fd 1')
