def step(planner):
    # into the drawer: 9 cm above its storage point, then let go
    goal = get_point_in_env(planner.env, "storage", "drawer", 0) + np.array([0.0, 0.0, 0.09])
    c = [Constraint(env=planner.env, type="point2point", end_effector_frame="l_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=0), object_key_point=goal),
         Const(env=planner.env, type="parallel", end_effector_frame="l_hand_base_link",
               hand_axis=get_axis_in_env(planner.env, "z", obj_type="cube", obj_id=0),
               object_axis=np.array([0.0, 0.0, 1.0]))]
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
