# Reference plan: both hands pinch a cube at once (the left one on the table, the right one on the platform,
# a barrier); the left hand sets cube 0 down on the table in the free strip between the left block and the
# platform, the right hand stacks cube 1 on it, then pinches cube 2 off the platform and stacks it on cube 1. Lifts
# are 10 cm: the carried cubes pass over the platform and the low block; the planner routes around the walls.
# step: both hands pinch their cubes at the same time (left: cube 0, right: cube 1)
planner.hand_pre_pinch("all")
c_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[False, False])
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift both cubes together
c_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                   relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                   relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[True, True],
                                object_name=["cube", "cube"], object_id=[0, 1])

# step: the left hand sets cube 0 down on the table at the middle of the table (y = 0) and lets go
p0 = get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0,
                                 relative_p=np.array([0.0, 0.0 - p0[1], 0.025 - p0[2]]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: the left hand goes back out of the way
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: the right hand carries cube 1 over cube 0, lowers it onto cube 0 and lets go
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.045]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")

# step: pinch cube 2 with the right hand and lift it
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=2)
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=2, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)

# step: carry cube 2 over cube 1, lower it onto cube 1 and let go
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.045]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)
planner.open_hand("right")

# step: take the right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
