# step: right hand grasps the door's handle bar
planner.hand_pre_grasp("right")
c = planner.generate_constraints("safe", 0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_grasp("right", grasp_object="safe", obj_id=0)

# step: swing the door open about its hinge in stages (27, 54, then 76 deg: openness 0.85, the most the prompt allows)
for openness in [0.3, 0.6, 0.85]:
    c = planner.generate_constraints("safe", 0, action="grasp", hand_name="right", openness=openness)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")

# step: let go of the handle and go home
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
