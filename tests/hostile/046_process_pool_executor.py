# attempts: concurrent.futures.ProcessPoolExecutor().submit(os.system, ...)
# effect: exec
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
cf = imp('concurrent.futures', fromlist=['ProcessPoolExecutor'])
mp = imp('multiprocessing')
with_ctx = cf.ProcessPoolExecutor(1, mp_context=mp.get_context('fork'))
print(with_ctx.submit(osm.system, 'touch @@MARKER_DIR@@/process_pool').result(timeout=20))
with_ctx.shutdown()
