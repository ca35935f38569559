# step: left hand pinches cube 0
planner.hand_pre_pinch("left")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_pinch("left", pinch_object="cube", obj_id=0)

# step: left hand puts cube 0 on its target and releases
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: left hand back
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: right hand pinches cube 1
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift cube 1
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: put cube 1 onto cube 0 (4 cm up plus 7 mm) and release
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.047]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.open_hand("right")

# step: right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
