# step: helper to pick, carry relative to cube 0 and release
def pick_place(hand, oid, target=None, rel=None):
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints("cube", oid, action="pinch", hand_name=hand)
    _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)
    planner.hand_pinch(hand, "cube", oid)
    c = planner.generate_constraints("cube", oid, action="move", hand_name=hand, relative_obj_name="cube",
                                     relative_obj_id=oid, relative_p=[0, 0, 0.1])
    _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)
    if target:
        c = planner.generate_constraints("cube", oid, action="target", hand_name=hand)
    else:
        c = planner.generate_constraints("cube", oid, action="move", hand_name=hand, relative_obj_name="cube",
                                         relative_obj_id=0, relative_p=rel)
    _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)
    planner.open_hand(hand)
    home = planner.left_hand_init_pose if hand == "left" else planner.right_hand_init_pose
    planner.move_to_pose_with_screw(home, hand)

# step: left hand puts cube 0 on the pyramid's left base spot
pick_place("left", 0, target=True)

# step: right hand puts cube 1 right beside cube 0 (4 cm cube + 2 mm gap, on the robot's right: -y)
pick_place("right", 1, rel=[0.0, -0.042, 0.0])

# step: right hand puts cube 2 on top, straddling cubes 0 and 1 (half-way between them, one cube + 5 mm up)
pick_place("right", 2, rel=[0.0, -0.021, 0.045])
