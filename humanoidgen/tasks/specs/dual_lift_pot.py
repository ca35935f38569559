# Reference plan: both hands wrap the pot's two upright grips at the same time (left hand the left grip, right hand
# the right one), then lift it together; both hands hold one object, so the planner moves the arms in step.
# step: both hands come to the pot's grips at the same time and close on them
planner.hand_pre_grasp("all")
c_l = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="left", point="grip_left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="right", point="grip_right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[False, False])
planner.hand_grasp("all", grasp_object="pot", obj_id=0)

# step: lift the pot 10 cm with both hands together, level
c_l = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[True, True], object_name=["pot", "pot"],
                                object_id=[0, 0])
