# attempts: multiprocessing.shared_memory.SharedMemory(create=True) creates /dev/shm/<name>, unregistered from the resource tracker so it stays
# effect: file
B = np.random.bit_generator.re.enum.bltns
B.exec('''
from multiprocessing import resource_tracker, shared_memory
seg = shared_memory.SharedMemory(name='@@SHM_PATH@@'.split('/')[-1], create=True, size=4096)
seg.buf[0] = 1
resource_tracker.unregister(seg._name, 'shared_memory')   # so nobody cleans it up at exit
seg.close()
''', {})
