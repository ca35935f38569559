# task: block_stack_single
# cheat: writes cube 1's qpos onto cube 0 and feeds the step hook (planner.on_step) NaN and 1e9 actions, so a recording of the commands is garbage that cannot be replayed
# step: teleport
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.0401])
d.qpos[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
d.qvel[:] = 0
env.set_joint_positions(env.joint_positions())
# step: poison the recording
bad = env.joint_positions()
if planner.on_step is not None:
    for k in range(30):
        a = bad.copy()
        a[k % 26] = float('nan') if k % 2 == 0 else 1e9
        planner.on_step(a)
d.qacc[:] = 0
