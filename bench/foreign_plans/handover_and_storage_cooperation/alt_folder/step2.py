def step(planner):
    # the left hand takes the block
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints("cube", 0, "pinch", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_pinch("left", "cube", 0)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
