# task coverage: the push targets with the author's own logging (print of the edge's position before and after,
# allowed plain Python), then the hand home.
# style: our `# step:` blocks.
# step: fingertip above the screen's top edge
edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0)
print("screen edge before:", [round(float(v), 3) for v in edge])
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: press the screen shut
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
edge = get_point_in_env(planner.env, "screen_edge", "laptop", 0)
print("screen edge after:", [round(float(v), 3) for v in edge])

# step: right hand home
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
