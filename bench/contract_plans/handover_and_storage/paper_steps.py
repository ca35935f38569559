# verb: carrying a pinched object through a long move (item 3), written step by step as the paper's task
# description reads: the left hand grasps the handle and pulls the drawer to openness 0.9, lets go; the right
# hand pinches the block and carries it to its hand-over target; the left hand pinches it (taking it from the
# right), carries it over the open drawer (target, left hand) and lets it drop in; then the left hand grasps
# the handle again and pushes the drawer back to openness 0.
# style: our `# step:` blocks, one per sentence of the paper's description.
# step: left hand grasps the drawer handle
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)

# step: pull the drawer out to openness 0.9 and let go of the handle
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.9)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: right hand pinches the block
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=0)

# step: right hand carries the block to the hand-over pose
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)

# step: left hand pinches the block, taking it from the right hand
planner.hand_pre_pinch("left")
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_pinch("left", pinch_object="cube", obj_id=0)

# step: right hand lets go and goes back
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand carries the block above the open drawer and drops it in
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")

# step: left hand grasps the handle again and pushes the drawer shut
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)

# step: release the handle and return the left hand
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
