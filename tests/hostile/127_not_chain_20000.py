# attempts: 20,000 chained `not` operators
# effect: parser
def step(planner):
    x = @@REPEAT:20000:not @@1
