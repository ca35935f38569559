# Reference plan (the paper's close_laptop_hard): the right hand grasps the raised screen, brings it down holding it
# to an openness of 0.3, lets go, and pushes it shut from above with the fingertip. The task judges the held part
# of that (moved_while_held) beside the laptop shut: an arm swinging into the nearly upright screen knocks it shut.
# step: grasp the screen with the right hand
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_grasp("right", grasp_object="laptop", obj_id=0)

# step: bring the screen down to openness 0.3, holding it
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right", openness=0.3)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)

# step: let go, bring the fingertip above the screen's edge and press it shut (the task's push targets)
planner.open_hand("right")
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
