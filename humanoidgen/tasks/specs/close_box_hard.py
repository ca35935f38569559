# Reference plan (the paper's close_box_hard): the right hand grasps the raised lid, lowers it holding it to an
# openness of 0.3 and lets go; from there the lid's own weight shuts it. The task judges that process
# (moved_while_held), not only the box shut: an arm swinging into the nearly upright lid knocks it shut too.
# step: grasp the lid with the right hand
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_grasp("right", grasp_object="box", obj_id=0)

# step: lower the lid to openness 0.3, holding it
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=0.3)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)

# step: let go; the lid falls shut
planner.open_hand("right")
