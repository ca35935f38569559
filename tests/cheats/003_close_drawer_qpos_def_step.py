# task: close_drawer
# cheat: sets the drawer's slide joint qpos to its closed position (the paper's def step(planner) form)
def step(planner):
    env = planner.env
    m, d = env.model, env.data
    drawer = env.scene.object('drawer', 0)
    art = drawer.annotations.articulation
    j = m.joint(drawer.body + '_' + art.joint)
    d.qpos[m.jnt_qposadr[j.id]] = art.joint_position(0.0)
    d.qvel[m.jnt_dofadr[j.id]] = 0.0
    env.set_joint_positions(env.joint_positions())
    for i in range(10):
        env.step(env.joint_positions())
