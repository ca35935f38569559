def step(planner):
    # Whole-hand grasp of cube1 from the top (grasp@top) instead of a pinch
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="cube", obj_id=1)
