# A README reader's plan: "target1" (the box's flip@lid_front) ridden down to openness 0.
# step: onto the lid's front tab
planner.hand_press("right")
c = planner.generate_constraints("box", 0, "target1", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: push the lid shut
c = planner.generate_constraints("box", 0, "target1", "right", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
