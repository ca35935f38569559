# task: close_drawer
# cheat: points model.opt.gravity along the drawer's closing direction so it slides shut by itself, then restores it
# step: tip the world
env = planner.env
m, d = env.model, env.data
drawer = env.scene.object('drawer', 0)
art = drawer.annotations.articulation
jid = m.joint(drawer.body + '_' + art.joint).id
closing = -np.array(d.xaxis[jid]) * (1.0 if art.open > art.closed else -1.0)
g0 = m.opt.gravity.copy()
m.opt.gravity[:] = 25.0 * closing + np.array([0.0, 0.0, -9.81])
hold = env.joint_positions()
for k in range(100):
    env.step(hold)
# step: put the world back
m.opt.gravity[:] = g0
for k in range(20):
    env.step(hold)
