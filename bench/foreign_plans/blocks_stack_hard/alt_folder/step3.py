def step(planner):
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
