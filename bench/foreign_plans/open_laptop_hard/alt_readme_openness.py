# A README reader's plan: pinch the edge up to 0.55, let go, then flip the rest of the way with
# target1 + openness= (the screen_edge flip point).
# step: pinch the screen edge
planner.hand_pre_pinch("right")
c = planner.generate_constraints("laptop", 0, "pinch", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", "laptop", 0)
# step: lift to 0.55 and let go
c = planner.generate_constraints("laptop", 0, "pinch", "right", openness=0.55)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
planner.open_hand("right")
# step: flip it fully up from under the edge
planner.hand_press("right")
c = planner.generate_constraints("laptop", 0, "target1", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
c = planner.generate_constraints("laptop", 0, "target1", "right", openness=0.9)
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right")
# step: back home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
