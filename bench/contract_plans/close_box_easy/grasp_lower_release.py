# verb: lowering a lid in stages with one hold (item 3) on the smaller box: the lid stands half open; the right
# hand grasps its tab, lowers it to 0.35, 0.2, 0.08 holding it, lets go just above shut, then presses it the
# rest of the way with the push targets.
# style: our `# step:` blocks; a helper for "solve and move", defined in the step that uses it.
# step: grasp the lid tab
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="box", obj_id=0)

# step: lower the lid almost shut with the same grasp
def lower_to(o):
    cons = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=o)
    _, p = planner.generate_end_effector_pose(cons, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="box", object_id=0)

for o in [0.35, 0.2, 0.08]:
    lower_to(o)
planner.open_hand("right")

# step: press the lid closed with the fingertip
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
