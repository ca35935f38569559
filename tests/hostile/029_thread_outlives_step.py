# attempts: a thread started in the step keeps writing a marker after the step has returned
# effect: file
# step: start a background writer
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
threading = imp('threading')
code = '''
import time
for i in range(60):
    time.sleep(0.1)
    try:
        open('@@MARKER_DIR@@/late_thread_write', 'w').write(str(i))
    except Exception:
        pass
'''
t = threading.Thread(target=B.exec, args=(code, {}), daemon=True)
t.start()
# step: return at once
x = 1
