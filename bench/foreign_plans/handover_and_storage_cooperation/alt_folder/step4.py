def step(planner):
    # shut the drawer by its handle and go home
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("drawer", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", "drawer", 0)
    c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.0)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
