# attempts: multiprocessing fork-context Process(target=os.system)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
mp = imp('multiprocessing')
p = mp.get_context('fork').Process(target=osm.system, args=('touch @@MARKER_DIR@@/mp_process',))
p.start()
p.join(20)
