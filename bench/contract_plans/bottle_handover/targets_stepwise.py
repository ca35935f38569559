# verb: grasp-to-grasp hand-over of a round body (item 3), on a new task spec (tasks/bottle_handover.yaml):
# the right hand grasps the bottle, brings it to its hand-over target (right hand), the left hand grasps it
# there ("an object the other hand holds: at the point farthest from that hand's grip"), the right lets go,
# the left carries it to its target (left hand) on the table and lets go.
# style: our `# step:` blocks, one action per step, as the prompt's rules list them.
# step: right hand grasps the bottle
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="bottle", obj_id=0)

# step: right hand brings the bottle to the hand-over pose
c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="bottle", object_id=0)

# step: left hand grasps the bottle from its side
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_grasp("left", grasp_object="bottle", obj_id=0)

# step: right hand lets go and returns
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand stands the bottle on the table on the left and lets go
c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="bottle", object_id=0)
planner.open_hand("left")

# step: left hand back to its initial pose
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
