# step: both hands get ready to pinch
planner.hand_pre_pinch("all")

# step: both hands move to their cubes at the same time (left: cube 0, right: cube 1) and pinch
cl = planner.generate_constraints("cube", 0, action="pinch", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(cl, hand_name="left")
cr = planner.generate_constraints("cube", 1, action="pinch", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all")
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift both cubes 10 cm together
cl = planner.generate_constraints("cube", 0, action="move", hand_name="left", relative_obj_name="cube", relative_obj_id=0, relative_p=[0, 0, 0.1])
_, pose_l = planner.generate_end_effector_pose(cl, hand_name="left")
cr = planner.generate_constraints("cube", 1, action="move", hand_name="right", relative_obj_name="cube", relative_obj_id=1, relative_p=[0, 0, 0.1])
_, pose_r = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all")

# step: left hand sets cube 0 on its target spot and lets go, then goes home
c = planner.generate_constraints("cube", 0, action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: right hand stacks cube 1 on cube 0 and lets go
c = planner.generate_constraints("cube", 1, action="move", hand_name="right", relative_obj_name="cube", relative_obj_id=0, relative_p=[0, 0, 0.046])
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.open_hand("right")

# step: right hand home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
