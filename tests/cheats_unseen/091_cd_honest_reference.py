# task: close_drawer
# honest: yes
# cheat: none: the task's reference plan (a control)
# Reference plan: the left index fingertip pushes the open drawer shut by its front face.
# step: bring the left fingertip to the open drawer's front
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_press("left")
# step: push it shut
planner.ignore_collision("drawer", 0)  # from here the fingertip pushes the front: contact is intended
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left", openness=0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.restore_collision("drawer", 0)
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
