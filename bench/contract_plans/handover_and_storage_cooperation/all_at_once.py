# verb: carrying a pinched object through a long move (item 3) while the other arm works: the right hand
# carries the pinched block to its intermediate target at the same time as the left hand pulls the drawer to
# openness 0.9 (hand_name="all", lists); then the left hand takes the block and carries it over the drawer,
# drops it in, and pushes the drawer shut with its push targets.
# style: our `# step:` blocks; simultaneous motions as the paper's description asks.
# step: left hand to the drawer handle and right hand to the block, at the same time
planner.hand_pre_grasp("left")
planner.hand_pre_pinch("right")
cl = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
cr = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[False, False])
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
planner.hand_pinch("right", pinch_object="cube", obj_id=0)

# step: pull the drawer to 0.9 while the right hand brings the block to the intermediate position
cl = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.9)
cr = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="right")
_, pl = planner.generate_end_effector_pose(cl, hand_name="left")
_, pr = planner.generate_end_effector_pose(cr, hand_name="right")
planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[True, True], object_name=["drawer", "cube"],
                                object_id=[0, 0])

# step: left hand lets go of the handle and pinches the block from the right hand
planner.open_hand("left")
planner.hand_pre_pinch("left")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand carries the block above the drawer and releases it
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: push the drawer shut with the left index fingertip
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target2", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
