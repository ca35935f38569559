# step: index finger out
planner.hand_press("right")

# step: fingertip onto the lever's top
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: press the lever all the way down (80 mm)
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: move the hand back up to its start
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
