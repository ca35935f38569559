# step: extend the right index finger
planner.hand_press("right")

# step: slip the fingertip under the lid's front tab (lid at 0.15 = 15 deg)
c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=0.15)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: flip the lid up: 40 deg, 70 deg, then fully open (100 deg)
for o in [0.4, 0.7, 1.0]:
    c = planner.generate_constraints("box", 0, action="flip", hand_name="right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: take the hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
