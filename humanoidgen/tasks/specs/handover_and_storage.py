# Reference plan for handover_and_storage: the left hand opens the drawer and lifts clear of it; the right hand picks the
# block and stands it on the table in the middle (the hand-over); the left hand takes it, raises it above the drawer's
# walls (the drawer is tall: its walls reach 24 cm), drops it into the open part of the drawer and pushes the drawer shut.
# step: left hand grasps the drawer handle and pulls the drawer open (most of its travel: 9/10 is well within the arm's reach), then lets go
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.9)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
planner.open_hand("left")
# lift the hand (and back it off a little) well clear of the open drawer, so that it does not drag it on the next moves
up = get_point_in_env(planner.env, "grasp_point_base_left_hand") + np.array([-0.03, 0, 0.10])
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="move", hand_name="left", relative_obj_name="drawer",
                                 relative_obj_id=0, relative_p=up - get_point_in_env(planner.env, "head", "drawer", 0))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")

# step: right hand pinches the block and lifts it
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)

# step: right hand hands the block over by standing it on the table in the middle, in the left hand's reach
handover = planner.workspace_point([-0.36, 0.0, 0.045]) - get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=handover)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand pinches the block and lifts it
planner.hand_pre_pinch("left")
# 2 cm further out than for a 4 cm cube: the index pad then meets the thin block's face instead of wrapping its
# corner (where the block gets squeezed out of the pinch when lifted)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left", finger_offset=0.02)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)

# step: left hand raises the block above the drawer's walls, carries it over the open drawer and drops it in
lift = planner.workspace_point(get_point_in_env(planner.env, "center", "cube", 0) * np.array([1, 1, 0]) + np.array([0, 0, 0.31]))
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0,
                                 relative_p=lift - get_point_in_env(planner.env, "center", "cube", 0))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
drop = get_point_in_env(planner.env, "storage", "drawer", 0) * np.array([1, 1, 0]) + np.array([-0.025, 0, 0.31])
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="drawer", relative_obj_id=0,
                                 relative_p=drop - get_point_in_env(planner.env, "head", "drawer", 0))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: left fingertip pushes the drawer shut by its front, then the hand goes back
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_press("left")
planner.ignore_collision("drawer", 0)  # from here the fingertip pushes the front: contact is intended
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left", openness=0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.restore_collision("drawer", 0)
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
