# Reference plan: the right hand wraps the empty cup from its right flank, lifts it, carries it over the plate,
# sets it down upright on the plate and lets go.
# step: the right hand grasps the cup around its body and lifts it
cup_z = get_point_in_env(planner.env, "center", "cup", 0)[2]  # the cup's centre height when it stands on the table
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="cup", obj_id=0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cup", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: carry the cup above the plate, lower it onto the plate and let go
on_plate = get_point_in_env(planner.env, "support", "plate", 0) - get_point_in_env(planner.env, "center", "plate", 0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=on_plate + np.array([0, -0.02, cup_z + 0.06]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=on_plate + np.array([0, -0.02, cup_z + 0.01]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
planner.open_hand("right")

# step: take the right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
