def step(planner):
    # The left hand moves cube0 to the stacking spot on its own (no simultaneous pinch)
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="cube", obj_id=0)
    spot = np.array([-0.33, 0.03, 0.024])
    for height in (0.10, 0.0):
        cons = [
            Constraint(env=planner.env, type="point2point", end_effector_frame="l_hand_base_link",
                       hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=0),
                       object_key_point=spot + np.array([0, 0, height])),
            Constraint(env=planner.env, type="parallel", end_effector_frame="l_hand_base_link",
                       hand_axis=get_axis_in_env(planner.env, axis_name="left_pinch_axis"),
                       object_axis=np.array([0, 0, -1])),
        ]
        _, pose = planner.generate_end_effector_pose(cons, "left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
