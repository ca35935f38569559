# Keep the cup upright all the way (path constraint), place it on the plate's support point from 8 cm above.
def step(planner):
    env = planner.env
    # Step 1: grasp the mug's side
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("cup", 0, "grasp", "right", point="side")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", "cup", 0)
    keep_upright = Constraint(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                              hand_axis=get_axis_in_env(env, "z", obj_type="cup", obj_id=0),
                              object_axis=np.array([0.0, 0.0, 1.0]))
    # Step 2: over the plate, then down
    support = get_point_in_env(env, "support", "plate", 0)
    half_height = 0.045
    for dz in (0.08, 0.005):
        goal = support + np.array([0.0, 0.0, half_height + dz])
        upright = Constraint(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                             hand_axis=get_axis_in_env(env, "z", obj_type="cup", obj_id=0),
                             object_axis=np.array([0.0, 0.0, 1.0]))
        cons = [Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                           hand_key_point=get_point_in_env(env, type_name="cup", obj_id=0),
                           object_key_point=goal), upright]
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0,
                                        path_constraints=[keep_upright])
    # Step 3: release and go home
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
