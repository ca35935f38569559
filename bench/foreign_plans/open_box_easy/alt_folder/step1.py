def step(planner):
    for o in (0.5, 0.95):
        c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right", openness=o)
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
