# Reference plan: both hands pinch a base cube at once; the left hand sets cube 0 down just left of the table's
# middle, the right hand sets cube 1 down just right of it (side by side), then the right hand pinches cube 2
# and lays it across the two.
GAP = 0.043  # centre distance the bases are set at (touching: 0.04, allowed up to 0.055); cube 1 drifts ~1 cm when dropped
BASE = np.array([-0.33, 0.07])  # the pyramid's middle on the table, kept 10+ cm from cube 2
DROP = 0.03  # cube 1 is let go 3 cm above the table: its fingers must clear cube 0 beside it

# step: both hands pinch their base cubes at the same time (left: cube 0, right: cube 1)
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

# step: the left hand sets cube 0 on the table half a gap left of the middle, lets go and goes back
p0 = get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0,
                                 relative_p=np.array([BASE[0] - p0[0], BASE[1] + GAP / 2 - p0[1], 0.026 - p0[2]]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: the right hand sets cube 1 down one gap to the right of cube 0, lets go and goes back
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, -GAP, DROP]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: the right hand pinches cube 2 and lifts it
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=2)
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=2, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)

# step: carry cube 2 above the middle of the two bases, lower it onto them and let go
mid = (get_point_in_env(planner.env, "center", "cube", 0) + get_point_in_env(planner.env, "center", "cube", 1)) / 2
to_mid = mid - get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=to_mid + np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)
c = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=to_mid + np.array([0, 0, 0.047]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=2)
planner.open_hand("right")

# step: take the right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
