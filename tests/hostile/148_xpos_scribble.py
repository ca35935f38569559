# attempts: write cube 1's derived world position (data.xpos) onto cube 0 without touching qpos: the judge reads derived state
# effect: cheat
# expect: failure
# needs: planner
d, m = planner.env.data, planner.env.model
d.xpos[m.body('cube_1').id] = d.xpos[m.body('cube_0').id] + np.array([0.0, 0.0, 0.04])
d.xmat[m.body('cube_1').id] = d.xmat[m.body('cube_0').id]
