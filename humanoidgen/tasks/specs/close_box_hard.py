# Reference plan for close_box_hard: the lid stands nearly upright, so the right index fingertip reaches over its
# front edge onto the outer face (the far side), pulls the lid toward the robot and then presses it down, in stages.
# Each stage aims the fingertip at that spot of the outer face, 3 cm in from the front edge, at a smaller openness.
# step: bring the right hand above the lid's front edge, extend the index finger and lower it onto the outer face
planner.hand_pre_grasp("right")
for o, lift in [(None, 0.05), (None, 0.0)]:
    edge = get_point_in_env(planner.env, "lid_front", "box", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="box", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="box", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.03 * edge_in - (0.012 + lift) * lid_in, name="fingertip on the lid"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=np.array([0.5, 0.0, -0.866]), lower=0.0, upper=np.radians(35), name="fingertip down")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    if lift > 0:
        planner.hand_press("right")
        planner.ignore_collision("box", 0)  # the fingertip is meant to touch the lid

# step: bring the lid down in stages until the box is closed, then lift the finger off
for o, lift in [(0.6, 0.0), (0.45, 0.0), (0.3, 0.0), (0.15, 0.0), (0.0, 0.0), (0.0, 0.05)]:
    edge = get_point_in_env(planner.env, "lid_front", "box", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="box", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="box", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.03 * edge_in - (0.012 + lift) * lid_in, name="fingertip on the lid"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=np.array([0.5, 0.0, -0.866]), lower=0.0, upper=np.radians(35), name="fingertip down")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: take the hand back
planner.restore_collision("box", 0)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
