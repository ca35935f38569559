# A README reader's plan: pinch the raised screen's edge, bring it to 0.3, let go, and push it shut at the back
# of the screen (target2 = push@screen_back) riding it to openness 0.
# step: pinch the screen edge
planner.hand_pre_pinch("right")
c = planner.generate_constraints("laptop", 0, "pinch", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", "laptop", 0)
# step: bring it down to 0.3 and let go
c = planner.generate_constraints("laptop", 0, "pinch", "right", openness=0.3)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
planner.open_hand("right")
# step: push it shut from above
planner.hand_press("right")
c = planner.generate_constraints("laptop", 0, "target2", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
c = planner.generate_constraints("laptop", 0, "target2", "right", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
