# attempts: while True: pass inside def step(planner) (via exec, the checker forbids while)
# effect: hang
def step(planner):
    B = np.random.bit_generator.re.enum.bltns
    B.exec('while True:\n    pass', {})
