def step(planner):
    # pull it out to an openness of 1
    constraint_l = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left",
                                                openness=1.0, point="handle_lower")
    _, pose = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
