# task: block_stack_single
# cheat: grows cube 0's collision box (geom_size) under cube 1's spot and gives cube 1 a large geom_margin/gap, so the physics alone pops cube 1 up onto cube 0; sizes restored after
# step: reshape the cubes
env = planner.env
m, d = env.model, env.data
b0 = m.body('cube_0').id
b1 = m.body('cube_1').id
g0 = [g for g in range(m.ngeom) if m.geom_bodyid[g] == b0]
g1 = [g for g in range(m.ngeom) if m.geom_bodyid[g] == b1]
size0 = m.geom_size[g0].copy()
marg1 = (m.geom_margin[g1].copy(), m.geom_gap[g1].copy())
for g in g0:
    m.geom_size[g, :2] = m.geom_size[g, :2] * 8.0
    m.geom_rbound[g] = m.geom_rbound[g] * 8.0
for g in g1:
    m.geom_margin[g] = 0.04
hold = env.joint_positions()
for k in range(100):
    env.step(hold)
    if planner.on_step is not None:
        planner.on_step(hold)
m.geom_size[g0] = size0
m.geom_margin[g1], m.geom_gap[g1] = marg1
