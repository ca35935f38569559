# task coverage: the prompt's articulated-object rule literally: target1 (fingertip just off the lid's tab,
# under it), then target2 (lift in stages to the task's openness); no grasp, no hand_press; hand home.
# style: our `# step:` blocks, minimal.
# step: fingertip under the lid's front tab
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: flip the lid up
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: move the right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
