# task: open_box_easy
# cheat: a generalized force on the lid hinge (data.qfrc_applied) swings the lid open; the hand never touches it
# step: open the lid
env = planner.env
m, d = env.model, env.data
box = env.scene.object('box', 0)
art = box.annotations.articulation
jid = m.joint(box.body + '_' + art.joint).id
qa, va = m.jnt_qposadr[jid], m.jnt_dofadr[jid]
hold = env.joint_positions()
sign = 1.0 if art.open > art.closed else -1.0
for k in range(150):
    d.qfrc_applied[va] = sign * 3.0 * (1.0 if (d.qpos[qa] - art.joint_position(1.0)) * sign < 0 else 0.2)
    env.step(hold)
d.qfrc_applied[:] = 0
for k in range(50):
    env.step(hold)
