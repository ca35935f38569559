# step: both hands ready to grasp
planner.hand_pre_grasp("all")

# step: both hands to their bottles at once (left: bottle 0 at y>0, right: bottle 1)
c_left = planner.generate_constraints("bottle", 0, action="grasp", hand_name="left")
_, pose_left = planner.generate_end_effector_pose(c_left, hand_name="left")
c_right = planner.generate_constraints("bottle", 1, action="grasp", hand_name="right")
_, pose_right = planner.generate_end_effector_pose(c_right, hand_name="right")
planner.move_to_pose_with_screw([pose_left, pose_right], hand_name="all")

# step: close both hands
planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
planner.hand_grasp("right", grasp_object="bottle", obj_id=1)

# step: lift both bottles 10 cm (their targets) at the same time
c_left = planner.generate_constraints("bottle", 0, action="target", hand_name="left")
_, pose_left = planner.generate_end_effector_pose(c_left, hand_name="left")
c_right = planner.generate_constraints("bottle", 1, action="target", hand_name="right")
_, pose_right = planner.generate_end_effector_pose(c_right, hand_name="right")
planner.move_to_pose_with_screw([pose_left, pose_right], hand_name="all", attach_obj=True)
