# Reference plan: the right hand picks up the block and hands it over by standing it upright on the table in the
# middle, within both hands' reach; the left hand takes it there and sets it upright on the cube.
HANDOVER = np.array([-0.34, 0.03])  # where the block changes hands


# step: the right hand pinches the block and lifts it
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)

# step: the right hand stands the block on the table in the middle, lets go and goes back out of the way
p = get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0,
                                 relative_p=planner.workspace_point([HANDOVER[0], HANDOVER[1], 0.041]) - p)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: the left hand pinches the block and lifts it
planner.hand_pre_pinch("left")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)

# step: the left hand carries the block above the cube, lowers it onto the cube and lets go
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.062]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: take the left hand back
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
