# step: onto the lever then force
planner.hand_press("right")
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
# step: force
c = planner.generate_constraints("toaster", 0, action="press", hand_name="right", force=5)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
