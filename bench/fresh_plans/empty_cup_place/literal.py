# step: grasp the cup with the right hand (it is at y < 0)
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="cup", obj_id=0)

# step: lift the cup
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cup", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: set the cup upright on the plate and let go
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
planner.open_hand("right")

# step: right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
