# step: left hand grasps the drawer handle
planner.hand_pre_grasp("left")
c = planner.generate_constraints("drawer", 0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_grasp("left", "drawer", 0)

# step: pull the drawer all the way out (openness 1 = 150 mm)
c = planner.generate_constraints("drawer", 0, action="grasp", hand_name="left", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")

# step: left hand lets go of the handle
planner.open_hand("left")

# step: right hand pinches the block and lifts it
planner.hand_pre_pinch("right")
c = planner.generate_constraints("rectangular_cube", action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", "rectangular_cube")
c = planner.generate_constraints("rectangular_cube", action="move", hand_name="right",
                                 relative_obj_name="rectangular_cube", relative_p=[0, 0, 0.1])
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: right hand brings the block to the hand-over pose
c = planner.generate_constraints("rectangular_cube", action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: left hand takes the block
planner.hand_pre_pinch("left")
c = planner.generate_constraints("rectangular_cube", action="pinch", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_pinch("left", "rectangular_cube")

# step: right hand releases and goes home
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand carries the block above the open drawer and drops it in
c = planner.generate_constraints("rectangular_cube", action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.open_hand("left")

# step: left hand pushes the drawer shut
c = planner.generate_constraints("drawer", 0, action="target1", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
c = planner.generate_constraints("drawer", 0, action="target2", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")

# step: left hand home
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
