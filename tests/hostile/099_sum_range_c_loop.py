# attempts: sum(range(10**15)): a C loop with no signal checks
# effect: hang
total = sum(range(10**15))
