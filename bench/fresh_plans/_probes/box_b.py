# step: fingertip on flip point at openness 0.15
planner.hand_press("right")
c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=0.15)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: to 1
c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
