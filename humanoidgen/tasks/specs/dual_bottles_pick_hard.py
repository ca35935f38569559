# Reference plan: each hand grasps one bottle by its side at the same time, and both lift them together.
# step: both hands grasp their bottles at the same time (left: bottle 0, right: bottle 1)
planner.hand_pre_grasp("all")
c_l = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="bottle", obj_id=1, action="grasp", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[False, False])
planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
planner.hand_grasp("right", grasp_object="bottle", obj_id=1)

# step: lift both bottles 10 cm, keeping them upright
c_l = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="bottle", obj_id=1, action="target", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[True, True],
                                object_name=["bottle", "bottle"], object_id=[0, 1])
