# step: press posture, fingertip on front where it is now
planner.hand_press("left")
c = planner.generate_constraints("drawer", 0, action="push", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
# step: push to 0.3 then 0
for o in [0.3, 0.0]:
    c = planner.generate_constraints("drawer", 0, action="push", hand_name="left", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left")
