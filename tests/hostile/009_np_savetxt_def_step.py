# attempts: np.savetxt via attrgetter, in the paper's def step(planner) form
# effect: file
def step(planner):
    # Step 1: write a text file
    savetxt = np.ma.core.operator.attrgetter('savetxt')(np)
    savetxt('@@MARKER_DIR@@/savetxt.txt', np.eye(3))
