# step: fingertip on the screen's back where it is now
planner.hand_press("right")
c = planner.generate_constraints("laptop", 0, action="push", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: push down in stages
for openness in (0.4, 0.25, 0.1, 0.0):
    c = planner.generate_constraints("laptop", 0, action="push", hand_name="right", openness=openness)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
