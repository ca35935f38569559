# A README reader's plan: the box's only push/flip annotation (flip@lid_front) is "target1"; flip it with openness=.
# step: get under the lid's front tab
planner.hand_press("right")
c = planner.generate_constraints("box", 0, "target1", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: flip the lid open past upright
c = planner.generate_constraints("box", 0, "target1", "right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
