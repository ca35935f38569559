# task: block_stack_single
# cheat: edits the model's initial configuration (model.qpos0: cube 1 on cube 0) and calls env.reset(), which rebuilds the state from it
# step: start over, stacked
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
m.qpos0[a0:a0 + 7] = d.qpos[a0:a0 + 7]
m.qpos0[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.0401])
m.qpos0[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
env.reset()
planner.hand_pre_pinch("right")
