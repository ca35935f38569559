# attempts: os._exit(0) in the middle of the plan: a clean exit code that pretends success
# effect: other
# needs: planner
# step: pinch, then vanish
planner.hand_pre_pinch("right")
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
osm = imp('os')
osm._exit(0)
