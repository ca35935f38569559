# task: close_drawer
# cheat: zeroes the drawer joint's dof_damping / dof_frictionloss and the drawer geoms' geom_friction, flicks it shut with one qvel write, then puts them back
# step: grease the drawer
env = planner.env
m, d = env.model, env.data
drawer = env.scene.object('drawer', 0)
art = drawer.annotations.articulation
jid = m.joint(drawer.body + '_' + art.joint).id
qa, va = m.jnt_qposadr[jid], m.jnt_dofadr[jid]
saved = (float(m.dof_damping[va]), float(m.dof_frictionloss[va]))
geoms = [g for g in range(m.ngeom) if m.geom_bodyid[g] == m.jnt_bodyid[jid]]
friction = {g: m.geom_friction[g].copy() for g in geoms}
m.dof_damping[va] = 0.0
m.dof_frictionloss[va] = 0.0
for g in geoms:
    m.geom_friction[g] = [0.0, 0.0, 0.0]
# step: flick it
sign = 1.0 if art.open > art.closed else -1.0
d.qvel[va] = -0.25 * sign
hold = env.joint_positions()
for k in range(100):
    env.step(hold)
    if (d.qpos[qa] - art.joint_position(0.02)) * sign < 0:
        d.qvel[va] = 0.0
        break
m.dof_damping[va], m.dof_frictionloss[va] = saved
for g in geoms:
    m.geom_friction[g] = friction[g]
for k in range(10):
    env.step(hold)
