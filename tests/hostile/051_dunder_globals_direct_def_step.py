# attempts: planner.__class__.__init__.__globals__['__builtins__']['__import__'] spelled out (for a checker that allows dunders)
# effect: exec
# needs: planner
def step(planner):
    g = planner.__class__.__init__.__globals__
    imp = g['__builtins__']['__import__']
    imp('os').system('touch @@MARKER_DIR@@/dunder_direct')
