# A README reader's plan (project's `# step:` format): push the back of the screen (push@screen_back is the
# laptop's second push/flip annotation, so "target2") down to openness 0 with `openness=`.
# step: go to the push point on the back of the screen
planner.hand_press("right")
c = planner.generate_constraints("laptop", 0, "target2", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: push it shut
c = planner.generate_constraints("laptop", 0, "target2", "right", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
