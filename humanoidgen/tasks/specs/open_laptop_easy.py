# Reference plan for open_laptop_easy: the right index fingertip slips under the ajar screen's top edge and lifts it
# in stages past upright (openness 0.92 asked, about 0.85 reached). Each stage puts the fingertip on the screen's
# underside, 3-5 cm in from the front edge (nearer the edge it slips off round it), with the screen further open.
# The palm faces sideways: with the palm down, the screen's weight curls the extended index finger and it slips.
# step: bring the right hand in front of the screen edge, extend the index finger and slide it under the edge
planner.hand_pre_grasp("right")
forward = get_axis_in_env(planner.env, "forward", obj_type="laptop", obj_id=0)
up = get_axis_in_env(planner.env, "up", obj_type="laptop", obj_id=0)
for back, s in [(0.05, 0.008), (0.0, 0.025)]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + s * edge_in + 0.013 * lid_in - back * forward, name="fingertip under the screen edge"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    if back > 0:
        planner.hand_press("right")
        planner.ignore_collision("laptop", 0)  # the fingertip is meant to touch the screen

# step: lift the screen in stages, pushing its underside further in from the edge as it rises, until it stands past upright
for o, s in [(0.3, 0.03), (0.45, 0.035), (0.6, 0.04), (0.72, 0.045), (0.84, 0.05), (0.92, 0.05)]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + s * edge_in + 0.013 * lid_in, name="fingertip on the screen's underside"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"),
                    object_axis=up, lower=np.radians(70), upper=np.radians(110), name="palm sideways")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: take the hand back
planner.restore_collision("laptop", 0)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
