# step: onto the lever
planner.hand_press("right")
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: press to openness 1
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
