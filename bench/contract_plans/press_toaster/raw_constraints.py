# verb: press (item 3), built from custom constraints because the action list has no press: the right press
# point 2 cm above lever_top with the press axis pointing down, then on the lever's top where it will be with
# the lever at openness 1 (get_point_in_env(..., openness=1.0)), then back up.
# style: our `# step:` blocks; every step recomputes its points (the prompt's rule).
# step: ready the right hand to press with the index fingertip
planner.hand_press("right")

# step: fingertip 2 cm above the lever, finger pointing down
env = planner.env
lever = get_point_in_env(env, "lever_top", "toaster", 0)
tip = get_point_in_env(env, "press_point_base_right_hand")
press_axis = get_axis_in_env(env, "right_press_axis")
down = get_axis_in_env(env, "down", "toaster", 0)
c = [
    Constraint(env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=lever + np.array([0, 0, 0.02])),
    Constraint(env, "parallel", "r_hand_base_link", hand_axis=press_axis, object_axis=down),
]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: push the lever down to the bottom of its travel
env = planner.env
bottom = get_point_in_env(env, "lever_top", "toaster", 0, openness=1.0)
tip = get_point_in_env(env, "press_point_base_right_hand")
press_axis = get_axis_in_env(env, "right_press_axis")
down = get_axis_in_env(env, "down", "toaster", 0)
c = [
    Constraint(env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=bottom - np.array([0, 0, 0.005])),
    Constraint(env, "parallel", "r_hand_base_link", hand_axis=press_axis, object_axis=down),
]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: lift the fingertip off and return the right hand
env = planner.env
lever = get_point_in_env(env, "lever_top", "toaster", 0)
tip = get_point_in_env(env, "press_point_base_right_hand")
c = [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=lever + np.array([0, 0, 0.08]))]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
