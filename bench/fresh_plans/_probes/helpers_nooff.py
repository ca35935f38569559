# step: define helpers for picking and placing with one hand
def pick(hand, obj, oid):
    planner.hand_pre_pinch(hand)
    cons = planner.generate_constraints(obj, oid, action="pinch", hand_name=hand)
    res, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)
    planner.hand_pinch(hand, pinch_object=obj, obj_id=oid)


def place_on(hand, obj, oid, ref, ref_id, dz):
    # above first, then down onto the reference
    for z in (dz + 0.08, dz):
        cons = planner.generate_constraints(obj, oid, action="move", hand_name=hand, relative_obj_name=ref,
                                            relative_obj_id=ref_id, relative_p=[0.0, 0.0, z])
        res, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
        planner.move_to_pose_with_screw(pose, hand)
    planner.open_hand(hand)


def home(hand):
    planner.move_to_pose_with_screw(planner.right_hand_init_pose if hand == "right" else planner.left_hand_init_pose, hand)

# step: choose the hand nearer to cube 1 and pick it up
p1 = get_point_in_env(planner.env, "center", "cube", 1)
hand = "left" if p1[1] > 0 else "right"
print("using", hand, "hand for cube 1 at", p1)
pick(hand, "cube", 1)

# step: stack cube 1 on cube 0 (4 cm cube + 5 mm clearance)
place_on(hand, "cube", 1, "cube", 0, 0.045)

# step: hand back home
home(hand)
