# Reference plan for close_laptop_easy: the right index fingertip presses the screen down from above, in stages.
# The screen's back faces away from the robot, so the fingertip presses the outer face near the top edge,
# pointing down and forward; each stage aims at that spot with the screen at a smaller openness.
# step: bring the right hand above the screen's top edge, extend the index finger and set it on the screen
planner.hand_pre_grasp("right")
for o, lift in [(None, 0.05), (None, 0.0)]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.015 * edge_in - (0.012 + lift) * lid_in, name="fingertip on the screen"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=np.array([0.5, 0.0, -0.866]), lower=0.0, upper=np.radians(35), name="fingertip down")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    if lift > 0:
        planner.hand_press("right")
        planner.ignore_collision("laptop", 0)  # the fingertip is meant to touch the screen

# step: press the screen down in stages until it is shut, then lift the finger off
for o, lift in [(0.35, 0.0), (0.2, 0.0), (0.08, 0.0), (0.0, 0.0), (0.0, 0.05)]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.015 * edge_in - (0.012 + lift) * lid_in, name="fingertip on the screen"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=np.array([0.5, 0.0, -0.866]), lower=0.0, upper=np.radians(35), name="fingertip down")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: take the hand back
planner.restore_collision("laptop", 0)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
