# step: pinch cube 1 from above
planner.hand_pre_pinch("right")
c = planner.generate_constraints("cube1", action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", "cube1")

# step: lift it straight up with my own constraints (cube centre 12 cm above the table, pinch axis kept)
env = planner.env
cube_c = get_point_in_env(env, "center", "cube", 1)
goal = cube_c + np.array([0.0, 0.0, 0.10])
pinch_ax = get_axis_in_env(env, "right_pinch_axis")
c = [
    Constraint(env, "point2point", "r_hand_base_link", hand_key_point=cube_c, object_key_point=goal, lower=0.0, upper=0.005),
    Constraint(env, "angle", "r_hand_base_link", hand_axis=pinch_ax, object_axis=pinch_ax, lower=0.0, upper=math.radians(10)),
]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: carry cube 1 over cube 0 and set it down 7 mm above cube 0's top face
env = planner.env
for clearance in (0.06, 0.007):
    cube_c = get_point_in_env(env, "center", "cube", 1)
    goal = get_point_in_env(env, "support", "cube", 0) + np.array([0.0, 0.0, 0.02 + clearance])
    pinch_ax = get_axis_in_env(env, "right_pinch_axis")
    c = [
        Constraint(env, "point2point", "r_hand_base_link", hand_key_point=cube_c, object_key_point=goal, lower=0.0, upper=0.004),
        Constraint(env, "angle", "r_hand_base_link", hand_axis=pinch_ax, object_axis=pinch_ax, lower=0.0, upper=math.radians(10)),
    ]
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
planner.open_hand("right")

# step: return the right hand
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
