# Reference plan (the paper's close_drawer): the left hand grasps the open drawer's handle, pushes the drawer shut
# while holding it, and lets go. The task judges that process (moved_while_held), not only the drawer shut: a
# fingertip or a swinging arm that knocks it shut does not do the task.
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

# step: let go of the handle (open_hand backs the hand off it; the paper's task ends here: taken back to its start
# pose, the arm found no path from under the cabinet's top on 1 of 50 seeds)
planner.open_hand("left")
