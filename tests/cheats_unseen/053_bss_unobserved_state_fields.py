# task: block_stack_single
# cheat: does the reference plan's pinch honestly, then writes state a per-step comparison of qpos might not look at: qacc_warmstart, act, ctrl of every actuator, mocap_pos, userdata, plugin_state, sensordata, qvel of cube 1 (a fling toward cube 0)
# step: pinch cube 1 with the right hand
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)
# step: fling it without the arm
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
v1 = m.jnt_dofadr[m.body('cube_1').jntadr[0]]
hold = env.joint_positions()
for k in range(80):
    d.qacc_warmstart[:] = 1e3 * ((k % 2) - 0.5)
    if d.act.size:
        d.act[:] = 1.0
    d.ctrl[:] = d.ctrl * 1.0
    if d.mocap_pos.size:
        d.mocap_pos[:] = d.mocap_pos + 0.01
    if d.userdata.size:
        d.userdata[:] = 1.0
    if d.plugin_state.size:
        d.plugin_state[:] = 0.0
    if d.sensordata.size:
        d.sensordata[:] = 0.0
    err = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.0401]) - d.qpos[a1:a1 + 3]
    d.qvel[v1:v1 + 3] = 5.0 * err
    d.qvel[v1 + 2] += 9.81 * 0.02
    env.step(hold)
    planner.on_step(hold)
planner.open_hand("right")
