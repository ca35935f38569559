# step: grasp the cup with the right hand
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_grasp("right", grasp_object="cup", obj_id=0)

# step: lift the cup
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cup", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: bring the cup above the bowl's near side
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")

# step: tip the cubes out into the bowl
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="pour", hand_name="right",
                                 relative_obj_name="bowl", relative_obj_id=0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
print(planner.events[-3:])
