# Explicit constraints throughout: the right hand holds the block low, keeps it upright at the handover point,
# and the left hand pinches its upper half from above.
def step(planner):
    env = planner.env
    up = np.array([0.0, 0.0, 1.0])
    down = np.array([0.0, 0.0, -1.0])

    # Step 1: right hand pinches the block from above
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints("cube", 0, "pinch", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", "cube", 0)

    # Step 2: carry it upright to the handover point in front of the chest
    handover = np.array([-0.31, -0.03, 0.16])
    cons = [
        Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                   hand_key_point=get_point_in_env(env, type_name="cube", obj_id=0), object_key_point=handover),
        Constraint(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                   hand_axis=get_axis_in_env(env, "z", obj_type="cube", obj_id=0), object_axis=up),
    ]
    _, pose = planner.generate_end_effector_pose(cons, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)

    # Step 3: left hand pinches the top part of the block from above
    planner.hand_pre_pinch("left")
    cons = [
        Constraint(env=env, type="point2point", end_effector_frame="l_hand_base_link",
                   hand_key_point=get_point_in_env(env, point_name="pinch_point_base_left_hand"),
                   object_key_point=get_point_in_env(env, type_name="cube", obj_id=0,
                                                     related_point=np.array([0.0, 0.0, 0.025]))),
        Constraint(env=env, type="parallel", end_effector_frame="l_hand_base_link",
                   hand_axis=get_axis_in_env(env, axis_name="left_pinch_axis"), object_axis=down),
    ]
    _, pose = planner.generate_end_effector_pose(cons, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_pinch("left", "cube", 0)

    # Step 4: right hand lets go
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)

    # Step 5: left hand puts the block on cube 1, upright, released 5 mm above
    target = get_point_in_env(env, type_name="cube", obj_id=1) + np.array([0.0, 0.0, 0.065])
    for lift in (0.06, 0.0):
        cons = [
            Constraint(env=env, type="point2point", end_effector_frame="l_hand_base_link",
                       hand_key_point=get_point_in_env(env, type_name="cube", obj_id=0),
                       object_key_point=target + np.array([0.0, 0.0, lift])),
            Constraint(env=env, type="parallel", end_effector_frame="l_hand_base_link",
                       hand_axis=get_axis_in_env(env, "z", obj_type="cube", obj_id=0), object_axis=up),
        ]
        _, pose = planner.generate_end_effector_pose(cons, "left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
