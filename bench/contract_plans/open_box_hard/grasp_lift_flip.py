# task coverage (a lid raised with one hold, then flipped): the right hand grasps the shut lid's tab, lifts it
# to openness 0.3 then 0.5 holding it, lets go, gets under it (target1) and flips it fully open (target2).
# style: our `# step:` blocks, the task description's order.
# step: grasp the lid tab
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="box", obj_id=0)

# step: lift the lid partway
for o in [0.3, 0.5]:
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)

# step: let go of the lid
planner.open_hand("right")

# step: get under the lid and flip it fully open
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
