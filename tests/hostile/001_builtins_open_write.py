# attempts: write a marker file with the real builtins.open, reached as np.random.bit_generator.re.enum.bltns
# effect: file
# step: write a marker file
B = np.random.bit_generator.re.enum.bltns
f = B.open('@@MARKER_DIR@@/escaped_open', 'w')
f.write('escaped through np.random.bit_generator.re.enum.bltns')
f.close()
