def step(planner):
    # grasp the lower part of the handle
    planner.hand_pre_grasp("left")
    constraint_l = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left",
                                                point="handle_lower")
    _, pose = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
