# attempts: set model.opt.gravity to 0 and teleport (tampers with the shared MjModel; later episodes must not inherit it)
# effect: cheat
# expect: failure
# needs: planner
m = planner.env.model
m.opt.gravity[:] = 0
d = planner.env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.04])
d.qvel[:] = 0
planner.env.set_joint_positions(planner.env.joint_positions())
