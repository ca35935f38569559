def step(planner):
    # both hands take hold at once: left on the drawer handle, right pinches the block (cube 0)
    planner.hand_pre_grasp("left")
    planner.hand_pre_pinch("right")
    _, pl = planner.generate_end_effector_pose(planner.generate_constraints("drawer", 0, "grasp", "left"), "left")
    _, pr = planner.generate_end_effector_pose(planner.generate_constraints("cube", 0, "pinch", "right"), "right")
    planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[False, False])
    planner.hand_grasp("left", "drawer", 0)
    planner.hand_pinch("right", "cube", 0)
