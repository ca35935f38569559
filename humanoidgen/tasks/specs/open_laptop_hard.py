# Reference plan for open_laptop_hard: the screen lies shut and flush on the base, with no room under its edge. So the
# right index fingertip first presses into the front of the edge and lifts it by friction in small steps (a big
# step slips off over the top) to about 0.1 openness, then slips under the edge and lifts it in stages past upright.
# The palm faces sideways: with the palm down, the screen's weight curls the extended index finger and it slips.
# step: bring the right hand in front of the shut screen's edge, extend the index finger and press it into the edge
planner.hand_pre_grasp("right")
forward = get_axis_in_env(planner.env, "forward", obj_type="laptop", obj_id=0)
up = get_axis_in_env(planner.env, "up", obj_type="laptop", obj_id=0)
for back in [0.05, 0.0]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.02 * edge_in + 0.003 * lid_in - back * forward, name="fingertip pressed into the edge"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"),
                    object_axis=up, lower=np.radians(70), upper=np.radians(95), name="palm sideways")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    if back > 0:
        planner.hand_press("right")
        planner.ignore_collision("laptop", 0)  # the fingertip is meant to touch the screen

# step: lift the edge by friction in small steps, still pressing into it, until the screen stands ajar
for o in [0.015, 0.03, 0.045, 0.06, 0.08, 0.1]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0, openness=o)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0, openness=o)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0, openness=o)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + 0.02 * edge_in + 0.003 * lid_in, name="fingertip pressed into the edge"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"),
                    object_axis=up, lower=np.radians(70), upper=np.radians(95), name="palm sideways")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: drop the fingertip below the ajar edge and slide it under, then lift the screen in stages past upright
for s, l in [(-0.015, 0.025), (0.025, 0.013)]:
    edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0)
    edge_in = get_axis_in_env(planner.env, "edge_in", obj_type="laptop", obj_id=0)
    lid_in = get_axis_in_env(planner.env, "lid_in", obj_type="laptop", obj_id=0)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                    object_key_point=edge + s * edge_in + l * lid_in, name="fingertip under the edge"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                    object_axis=forward, lower=0.0, upper=np.radians(40), name="fingertip points forward"),
         Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"),
                    object_axis=up, lower=np.radians(70), upper=np.radians(95), name="palm sideways")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
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
                    object_axis=up, lower=np.radians(70), upper=np.radians(95), name="palm sideways")]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: take the hand back
planner.restore_collision("laptop", 0)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
