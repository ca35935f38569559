# step: fingertip to the pre-push pose just off the screen's top edge
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: lift the screen from under its edge and flip it up
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: right hand home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
