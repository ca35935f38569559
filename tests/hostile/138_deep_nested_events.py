# attempts: planner.events.append of a 100,000-deep nested list (serialisation recursion)
# effect: other
# needs: planner
x = []
for i in range(100000):
    x = [x]
planner.events.append(x)
