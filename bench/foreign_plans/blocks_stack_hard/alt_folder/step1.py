def step(planner):
    # The right hand stacks cube1 on cube0: pinch, and if no pinch pose is found, grasp it instead
    try:
        planner.hand_pre_pinch("right")
        c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
        planner.hand_pinch("right", pinch_object="cube", obj_id=1)
    except Exception as e:
        print("pinch failed, grasping instead:", e)
        planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
        planner.hand_pre_grasp("right")
        c = planner.generate_constraints(obj_name="cube", obj_id=1, action="grasp", hand_name="right")
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
        planner.hand_grasp("right", grasp_object="cube", obj_id=1)
    for dz in (0.10, 0.045):
        c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                         relative_obj_name="cube", relative_obj_id=0,
                                         relative_p=np.array([0, 0, dz]))
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
