# verb: lowering a lid in stages with one hold (item 3), on the laptop: the right hand grasps the screen over
# its top edge (grasp@screen_grip) and brings it down to 0.55, 0.4, 0.3 holding it (the paper: "adjusts the
# laptop screen's openness to 0.3"), releases, and pushes it shut with target1/target2.
# style: our `# step:` blocks, a for loop.
# step: grasp the laptop screen with the right hand
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="laptop", obj_id=0)

# step: bring the screen down to openness 0.3 in stages, still grasping it
for openness in (0.55, 0.4, 0.3):
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right", openness=openness)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)

# step: release the screen
planner.open_hand("right")

# step: push the screen fully down from above
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
