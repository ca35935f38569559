# task coverage, the openness of a part with two moving parts: the right hand grasps the door's handle bar and
# pulls the door open in three stages (openness 0.3, 0.55, 0.8) with one grasp; `openness=` with the handle's
# grasp is taken to mean the door (the handle's part). Release, hand home.
# style: our `# step:` blocks; a for loop.
# step: grasp the handle bar
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="safe", obj_id=0)

# step: swing the door open in stages
for o in (0.3, 0.55, 0.8):
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)

# step: let go and bring the hand back
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
