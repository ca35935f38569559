def step(planner):
    # bring the screen down to 0.3 while holding it
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right", openness=0.3)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    planner.open_hand("right")
