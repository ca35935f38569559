# attempts: print('A' * 20_000_000)
# effect: output
print('A' * 20_000_000)
