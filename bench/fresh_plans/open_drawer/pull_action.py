# step: let the left hand touch the drawer and get ready to grasp
planner.ignore_collision("drawer", 0)
planner.hand_pre_grasp("left")

# step: grasp the handle from above (upper side of the bar)
c = planner.generate_constraints("drawer", 0, action="grasp", hand_name="left", point="handle_upper")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
planner.hand_grasp("left", "drawer", 0)

# step: pull the drawer out in three stages (5 cm, 10 cm, 15 cm)
for o in [0.33, 0.66, 1.0]:
    c = planner.generate_constraints("drawer", 0, action="pull", hand_name="left", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left")

# step: release, restore collisions and go home
planner.open_hand("left")
planner.restore_collision("drawer", 0)
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
