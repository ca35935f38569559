# step: pinch cube 1 with the right hand
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift cube 1 by 10 cm
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)

# step: put cube 1 on its target on top of cube 0 and release it
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")

# step: move the right hand back to its initial pose
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
