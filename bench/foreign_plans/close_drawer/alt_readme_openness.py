# A README reader's plan: push the drawer front (push@front, "target1") in to openness 0 with the fingertips.
# step: to the drawer front
planner.hand_press("left")
c = planner.generate_constraints("drawer", 0, "target1", "left")
_, pose = planner.generate_end_effector_pose(c, "left")
planner.move_to_pose_with_screw(pose, "left")
# step: push it shut
c = planner.generate_constraints("drawer", 0, "target1", "left", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, "left")
planner.move_to_pose_with_screw(pose, "left")
# step: back home
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
