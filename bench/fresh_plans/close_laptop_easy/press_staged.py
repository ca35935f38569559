# step: extend the right index finger
planner.hand_press("right")

# step: fingertip on the back of the screen near its top edge (screen at 0.55 = about 60 deg)
c = planner.generate_constraints("laptop", 0, action="push", hand_name="right", openness=0.55)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: push the screen down from above in stages until it is shut
for openness in (0.4, 0.25, 0.1, 0.0):
    c = planner.generate_constraints("laptop", 0, action="push", hand_name="right", openness=openness)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: lift the finger off and go home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
