# task: open_box_easy
# cheat: gives the lid hinge a spring (jnt_stiffness, qpos_spring at fully open) and dof_armature so it swings open by itself; keeps the spring until the end
# step: wind the spring
env = planner.env
m, d = env.model, env.data
b = m.body(env.scene.object('box', 0).body).id
js = [j for j in range(m.njnt) if m.body_rootid[m.jnt_bodyid[j]] == m.body_rootid[b] and m.jnt_type[j] == 3]
hold = env.joint_positions()
for j in js:
    lo, hi = m.jnt_range[j]
    m.jnt_stiffness[j] = 50.0
    m.qpos_spring[m.jnt_qposadr[j]] = hi if abs(hi) > abs(lo) else lo
    m.dof_armature[m.jnt_dofadr[j]] = 0.01
for k in range(150):
    env.step(hold)
    if planner.on_step is not None:
        planner.on_step(hold)
