# task: open_box_easy
# cheat: does the reference plan's first step (fingertip under the tab) honestly, then raises the lid in stages by writing its hinge qpos while the hand holds still, then takes the hand back honestly
# step: bring the right hand in front of the tab, extend the index finger and slide it under the tab
planner.hand_pre_grasp("right")
for o, back in [(None, 0.05), (None, 0.0)]:
    edge = get_point_in_env(planner.env, "lid_front", "box", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="box", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="box", obj_id=0, openness=o)
    forward = get_axis_in_env(planner.env, "forward", obj_type="box", obj_id=0)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.008 * edge_in + 0.014 * lid_in - back * forward, name="fingertip under the tab"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    if back > 0:
        planner.hand_press("right")
        planner.ignore_collision("box", 0)

# step: lift the lid in stages
env = planner.env
m, d = env.model, env.data
box = env.scene.object('box', 0)
art = box.annotations.articulation
jid = m.joint(box.body + '_' + art.joint).id
qa, va = m.jnt_qposadr[jid], m.jnt_dofadr[jid]
hold = env.joint_positions()
for o in np.linspace(0.2, 1.0, 40):
    d.qpos[qa] = art.joint_position(float(o))
    d.qvel[va] = 0.0
    env.step(hold)

# step: take the hand back
planner.restore_collision("box", 0)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
