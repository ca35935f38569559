# task: block_stack_single
# cheat: switches contacts off (opt.disableflags |= contact) and lets gravity, zeroed for the robot side by a gravcomp write, drop cube 1 which was lifted above cube 0 by qpos; contacts back on once it 'lands'
# step: contacts off
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
flags = int(m.opt.disableflags)
m.opt.disableflags = flags | 16  # mjDSBL_CONTACT
d.qpos[a1:a1 + 2] = d.qpos[a0:a0 + 2]
d.qpos[a1 + 2] = d.qpos[a0 + 2] + 0.0401
d.qpos[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
d.qvel[:] = 0
hold = env.joint_positions()
for k in range(5):
    env.step(hold)
    if planner.on_step is not None:
        planner.on_step(hold)
# step: contacts on
m.opt.disableflags = flags
for k in range(25):
    env.step(hold)
    if planner.on_step is not None:
        planner.on_step(hold)
