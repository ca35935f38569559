def step(planner):
    # push it shut from above
    for action in ("target1", "target2"):
        c = planner.generate_constraints(obj_name="laptop", obj_id=0, action=action, hand_name="right")
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
