# verb: press (item 3) on a new task spec (tasks/press_toaster_left.yaml), from custom constraints: the left
# press point above the lever, press axis down, then 1 cm under the lever's top at openness 1 (the fingertip
# follows the lever to the bottom), then up and home. A weighted cost (Const) keeps the palm facing forward-down.
# style: our `# step:` blocks, numbers carried only within a step.
# step: ready the left hand to press
planner.hand_press("left")

# step: fingertip just above the lever of the toaster
env = planner.env
lever = get_point_in_env(env, "lever_top", "toaster", 0)
tip = get_point_in_env(env, "press_point_base_left_hand")
c = [Constraint(env, "point2point", "l_hand_base_link", hand_key_point=tip, object_key_point=lever + np.array([0, 0, 0.015])),
     Constraint(env, "parallel", "l_hand_base_link", hand_axis=get_axis_in_env(env, "left_press_axis"),
                object_axis=get_axis_in_env(env, "down", "toaster", 0)),
     Const(env, "parallel", "l_hand_base_link", hand_axis=get_axis_in_env(env, "left_ring_2_index"),
           object_axis=get_axis_in_env(env, "forward", "toaster", 0), weight=0.2)]
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)

# step: press the lever all the way down
env = planner.env
low = get_point_in_env(env, "lever_top", "toaster", 0, openness=1.0)
tip = get_point_in_env(env, "press_point_base_left_hand")
c = [Constraint(env, "point2point", "l_hand_base_link", hand_key_point=tip, object_key_point=low - np.array([0, 0, 0.01])),
     Constraint(env, "parallel", "l_hand_base_link", hand_axis=get_axis_in_env(env, "left_press_axis"),
                object_axis=get_axis_in_env(env, "down", "toaster", 0))]
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)

# step: release: lift the finger and return the left hand
env = planner.env
tip = get_point_in_env(env, "press_point_base_left_hand")
c = [Constraint(env, "point2point", "l_hand_base_link", hand_key_point=tip, object_key_point=tip + np.array([0, 0, 0.1]))]
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
