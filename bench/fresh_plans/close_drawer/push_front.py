# step: left index finger out, ready to push
planner.hand_press("left")

# step: fingertip onto the drawer's front where it is now (openness 0.6)
c = planner.generate_constraints("drawer", 0, action="push", hand_name="left", openness=0.6)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")

# step: push the drawer shut in two stages (0.3, then 0 = closed)
for o in [0.3, 0.0]:
    c = planner.generate_constraints("drawer", 0, action="push", hand_name="left", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left")

# step: back off and take the left hand home
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
