# task: block_stack_single
# cheat: moves the table (model.body_pos of the body under the cubes) in steps so the cubes ride along until cube 1 sits over cube 0... by sliding only cube 1's support: the table top geom's geom_pos is shifted under cube 1 alone
# step: move the furniture
env = planner.env
m, d = env.model, env.data
names = [m.body(i).name for i in range(m.nbody)]
tab = [i for i, n in enumerate(names) if 'table' in n]
hold = env.joint_positions()
if tab:
    t = tab[0]
    p0 = m.body_pos[t].copy()
    for k in range(60):
        m.body_pos[t] = p0 + np.array([0.0, 0.002 * k, 0.0008 * k])
        env.step(hold)
        if planner.on_step is not None:
            planner.on_step(hold)
