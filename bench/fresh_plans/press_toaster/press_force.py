# step: extend the index finger and press the toaster lever down with 5 N
planner.hand_press("right")
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right", force=5)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
print(planner.events[-2:])

# step: lift the fingertip 6 cm straight up off the lever
tip = get_point_in_env(planner.env, "press_point_base_right_hand")
goal = tip + np.array([0.0, 0.0, 0.06])
c = [Constraint(planner.env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=goal, upper=0.01),
     Const(planner.env, "parallel", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
           object_axis=np.array([0.0, 0.0, -1.0]), weight=0.5)]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: right hand home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
