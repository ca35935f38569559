# task coverage: the cup carried with action="move" (no use of its target): lifted 12 cm, brought over the
# plate (12 cm above it), lowered to 6.5 cm above the plate's centre (the cup's half height 4.5 cm, the plate
# about 1 cm thick, 1 cm to spare), released, hand home.
# style: our `# step:` blocks; relative_p in world metres from the plate's centre.
# step: grasp the cup with the right hand (it is on the right)
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="cup", obj_id=0)

# step: lift the cup
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="cup", relative_obj_id=0, relative_p=np.array([0, 0, 0.12]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: carry it over the plate
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=np.array([0, -0.02, 0.12]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: lower it onto the plate and let go
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=np.array([0, -0.02, 0.065]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
