# step: left hand grasps the drawer handle
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)

# step: pull the drawer all the way out (openness 1.0 = 150 mm)
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")

# step: let go and take the left hand back
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
