# Reference plan: the right hand wraps the cup (two cubes inside) from its right flank, lifts it, holds it above
# the near side of the bowl, tips it toward the bowl until the cubes slide out, and sets it upright again.
# step: the right hand grasps the cup around its body and lifts it
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="cup", obj_id=0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cup", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: carry the cup, still upright, above the bowl's near (right) side
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="bowl", relative_obj_id=0, relative_p=[0, -0.07, 0.19])
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: tip the cup toward the bowl until its opening faces nearly down and the cubes fall in
up = get_axis_in_env(planner.env, "z", "cup", 0)  # the cup's axis, which turns with the hand from here on
centre = get_point_in_env(planner.env, "center", "cup", 0)
over = get_point_in_env(planner.env, "center", "bowl", 0) + np.array([0, -0.06, 0.19])
c = [Constraint(planner.env, "point2point", "r_hand_base_link", hand_key_point=centre, object_key_point=over,
                name="cup beside the bowl's middle"),
     Constraint(planner.env, "parallel", "r_hand_base_link", hand_axis=up, object_axis=np.array([0, 0.34, -0.94]),
                name="cup tipped 160 deg toward the bowl")]
# (at 130 deg the cubes still stick to the cup wall: wood on ceramic holds up to about 40 deg of slope)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: turn the empty cup upright again above the table
c = [Constraint(planner.env, "point2point", "r_hand_base_link", hand_key_point=get_point_in_env(planner.env, "center", "cup", 0),
                object_key_point=over + np.array([0, -0.04, 0.0]), name="cup back beside the bowl"),
     Constraint(planner.env, "parallel", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "z", "cup", 0),
                object_axis=np.array([0, 0, 1.0]), name="cup upright")]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
