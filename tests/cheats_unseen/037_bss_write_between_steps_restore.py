# task: block_stack_single
# cheat: keeps cube 1 on cube 0 only while physics runs, restoring its true pose right after each step (so a per-step check of the configuration sees the original), then leaves it stacked at the end
# step: stack between the samples
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
orig = d.qpos[a1:a1 + 7].copy()
goal = d.qpos[a0:a0 + 7].copy()
goal[2] += 0.0401
hold = env.joint_positions()
for k in range(60):
    d.qpos[a1:a1 + 7] = goal
    env.step(hold)
    d.qpos[a1:a1 + 7] = orig
d.qpos[a1:a1 + 7] = goal
d.qvel[:] = 0
env.set_joint_positions(hold)
