# task: block_stack_single
# cheat: writes cube 1 onto cube 0 and feeds the recording finite but absurd commands (1e300, -1e300, 1e-320 subnormals, values far outside ctrlrange) that a clip-free replay would turn into superhuman forces
# step: teleport
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.0401])
d.qpos[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
d.qvel[:] = 0
env.set_joint_positions(env.joint_positions())
# step: absurd commands
base = env.joint_positions()
for k in range(40):
    a = base.copy()
    a[k % 26] = [1e300, -1e300, 1e-320, 1e6][k % 4]
    if planner.on_step is not None:
        planner.on_step(a)
