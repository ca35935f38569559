# step: press posture, fingertip on the flip point where it is now
planner.hand_press("right")
c = planner.generate_constraints("box", 0, action="flip", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: flip to 1
c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
