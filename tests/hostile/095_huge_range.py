# attempts: for i in range(10**15): pass (plain checker-legal Python)
# effect: hang
# step: count for ever
for i in range(10**15):
    pass
