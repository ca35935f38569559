# attempts: [x for x in itertools.repeat(1)]: an unbounded comprehension
# effect: memory
x = [v for v in np.ma.extras.itertools.repeat(1.0)]
