# task: close_drawer
# honest: yes
# cheat: none: the task's reference plan (a control)
# (Since e1d489e close_drawer asks the drawer pushed shut by the left hand holding its handle; this control, written
# as the fingertip push the reference plan was then, follows the reference plan as it is now.)
# Reference plan: the left hand grasps the open drawer's handle, pushes it shut holding it, and lets go.
# step: grasp the handle with the left hand
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
# step: push the drawer shut, holding its handle
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
# step: let go of the handle
planner.open_hand("left")
