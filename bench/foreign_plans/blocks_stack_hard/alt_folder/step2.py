def step(planner):
    # Cube2 goes on top: 8.5 cm above cube0's centre (two 4 cm cubes plus 5 mm)
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=2, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=2)
    for dz in (0.14, 0.085):
        c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                         relative_obj_name="cube", relative_obj_id=0,
                                         relative_p=np.array([0, 0, dz]))
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)
    planner.open_hand("right")
