# task: block_stack_single
# cheat: sets model.opt.timestep to 1e-9 (the world stops) after placing cube 1 hovering over cube 0 by qpos
# step: place cube 1 above cube 0
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.012, -0.012, 0.045])  # hovering, a bit off centre
d.qpos[a1 + 3:a1 + 7] = np.array([0.92388, 0.0, 0.0, 0.38268])  # turned 45 deg
d.qvel[:] = 0
env.set_joint_positions(env.joint_positions())
# step: stop time
m.opt.timestep = 1e-9
for k in range(50):
    env.step(env.joint_positions())
