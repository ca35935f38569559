def step(planner):
    # Flip with a pinch of the front tab, lifted in stages
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="box", obj_id=0)
