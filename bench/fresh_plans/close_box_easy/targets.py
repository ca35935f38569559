# step: index fingertip to the pre-push pose just off the lid's front
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: push the lid down until the box is closed
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: right hand back to its start
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
