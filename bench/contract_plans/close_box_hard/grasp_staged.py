# verb: lowering a lid in stages with one hold (item 3): the right hand grasps the raised lid at its tab and,
# without letting go, brings it down to openness 0.6, 0.45, 0.3 (a for loop, one grasp); then lets go and
# presses it shut with the task's push targets (target1: fingertip above the lid, target2: press to 0).
# style: our `# step:` blocks, a for loop over openness values.
# step: right hand grasps the box lid's tab
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="box", obj_id=0)

# step: lower the lid in stages, keeping hold of it
for openness in [0.6, 0.45, 0.3]:
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=openness)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)

# step: let go of the lid
planner.open_hand("right")

# step: press the lid shut from above with the index fingertip
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: right hand back to its initial pose
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
