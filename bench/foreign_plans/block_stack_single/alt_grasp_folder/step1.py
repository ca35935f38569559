def step(planner):
    # Carry cube1 high above cube0 first (avoids sweeping it across cube0)
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                     relative_obj_name="cube", relative_obj_id=0,
                                     relative_p=np.array([0.0, 0.0, 0.10]))
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
