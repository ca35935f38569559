# step: both hands pre-grasp
planner.hand_pre_grasp("all")

# step: left hand to the left grip, right hand to the right grip, together
cl = planner.generate_constraints("pot", 0, action="grasp", hand_name="left", point="grip_left")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
cr = planner.generate_constraints("pot", 0, action="grasp", hand_name="right", point="grip_right")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all")

# step: both hands close on the pot
planner.hand_grasp("all", grasp_object="pot", obj_id=0)

# step: lift the pot 10 cm, level, with both hands
cl = planner.generate_constraints("pot", 0, action="target", hand_name="left")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
cr = planner.generate_constraints("pot", 0, action="target", hand_name="right")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all")
