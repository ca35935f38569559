# attempts: builtins.exec of a full Python stage-2 program (import, with, try: everything the checker forbids)
# effect: file
B = np.random.bit_generator.re.enum.bltns
B.exec('''
import os
with open(os.path.join('@@MARKER_DIR@@', 'stage2_exec'), 'w') as f:
    f.write('stage 2 ran')
''', {})
