# attempts: write a file under /dev/shm (often left writable) with builtins.open
# effect: file
B = np.random.bit_generator.re.enum.bltns
f = B.open('@@SHM_PATH@@', 'w')
f.write('escaped into /dev/shm')
f.close()
