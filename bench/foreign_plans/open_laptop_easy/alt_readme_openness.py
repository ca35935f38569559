# A README reader's plan (project's own `# step:` format): the push/flip action with `openness=`
# ("pushing a part to an openness rides with the part"); target1 is the laptop's first flip point (screen_edge).
# step: fingertip posture and go to the flip point under the screen edge
planner.hand_press("right")
c = planner.generate_constraints("laptop", 0, "target1", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: flip the screen up to openness 0.9, riding with it
c = planner.generate_constraints("laptop", 0, "target1", "right", openness=0.9)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
