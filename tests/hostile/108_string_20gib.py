# attempts: 'A' * (20 * 2**30)
# effect: memory
s = 'A' * (20 * 2**30)
