# task: close_drawer
# cheat: narrows the drawer slide's model.jnt_range to [closed, closed + 2 mm]: the joint limit shoves it shut
# step: shrink the drawer's travel
env = planner.env
m, d = env.model, env.data
drawer = env.scene.object('drawer', 0)
art = drawer.annotations.articulation
jid = m.joint(drawer.body + '_' + art.joint).id
old = m.jnt_range[jid].copy()
m.jnt_limited[jid] = 1
lo = min(art.joint_position(0.0), art.joint_position(0.013))
m.jnt_range[jid] = [lo, lo + 0.002]
hold = env.joint_positions()
for k in range(100):
    env.step(hold)
# step: give it its travel back
m.jnt_range[jid] = old
for k in range(10):
    env.step(hold)
