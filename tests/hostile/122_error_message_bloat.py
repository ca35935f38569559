# attempts: raise ValueError('X' * 100_000_000): a 100 MB error message
# effect: output
def step(planner):
    raise ValueError('X' * 100_000_000)
