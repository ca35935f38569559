# task: open_box_easy
# cheat: gives the lid hinge negative model.dof_damping (it speeds itself up) plus a small nudge: it swings open on its own
# step: let the lid run away
env = planner.env
m, d = env.model, env.data
box = env.scene.object('box', 0)
art = box.annotations.articulation
jid = m.joint(box.body + '_' + art.joint).id
qa, va = m.jnt_qposadr[jid], m.jnt_dofadr[jid]
sign = 1.0 if art.open > art.closed else -1.0
old = float(m.dof_damping[va])
m.dof_damping[va] = -0.2
d.qvel[va] = 2.0 * sign
hold = env.joint_positions()
for k in range(250):
    env.step(hold)
    if (d.qpos[qa] - art.joint_position(0.98)) * sign > 0:
        break
m.dof_damping[va] = old
for k in range(50):
    env.step(hold)
