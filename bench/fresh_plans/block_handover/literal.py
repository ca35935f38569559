# step: right hand pinches the block
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="rectangular_cube", action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", pinch_object="rectangular_cube")

# step: lift the block
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: right hand brings the block to the hand-over pose
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: left hand takes the block (pinching its free end)
planner.hand_pre_pinch("left")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left", point="pinch_bottom")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_pinch("left", pinch_object="cube", obj_id=0)

# step: right hand lets go and goes home
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand stands the block on the target cube and releases
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target2", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.open_hand("left")

# step: left hand home
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
