# step: fingertip on flip point as it is now
planner.hand_press("right")
c = planner.generate_constraints("box", 0, action="flip", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: staged
for o in [0.4, 0.7, 1.0]:
    c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
