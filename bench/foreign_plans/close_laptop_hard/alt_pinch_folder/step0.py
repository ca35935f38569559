def step(planner):
    # the laptop's annotations offer a pinch of the screen edge (no grasp): pinch it
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="laptop", obj_id=0)
