# attempts: bytearray(30 * 2**30)
# effect: memory
x = np.random.bit_generator.re.enum.bltns.bytearray(30 * 2**30)
