# task coverage: both arms at once (hand_name="all", list arguments, index 0 left, 1 right) for the grasp and
# for the lift to each bottle's target.
# style: our `# step:` blocks with the paper's list conventions.
# step: both hands ready to grasp
planner.hand_pre_grasp("all")

# step: both hands to their bottles at the same time and grasp
cl = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="left")
cr = planner.generate_constraints(obj_name="bottle", obj_id=1, action="grasp", hand_name="right")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[False, False])
planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
planner.hand_grasp("right", grasp_object="bottle", obj_id=1)

# step: lift both bottles to their targets together
cl = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target", hand_name="left")
cr = planner.generate_constraints(obj_name="bottle", obj_id=1, action="target", hand_name="right")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[True, True], object_name=["bottle", "bottle"],
                                object_id=[0, 1])
