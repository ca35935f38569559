# step: helpers
def hand_for(obj, oid):
    p = get_point_in_env(planner.env, "center", obj, oid)
    return "left" if p[1] > 0 else "right"


def init_pose(hand):
    return planner.left_hand_init_pose if hand == "left" else planner.right_hand_init_pose


def pinch(hand, oid):
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints("cube", oid, action="pinch", hand_name=hand)
    _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)
    planner.hand_pinch(hand, "cube", oid)


def lift(hand, oid, dz=0.1):
    c = planner.generate_constraints("cube", oid, action="move", hand_name=hand, relative_obj_name="cube",
                                     relative_obj_id=oid, relative_p=[0, 0, dz])
    _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand)

# step: cube 0 to the stacking spot
h = hand_for("cube", 0)
pinch(h, 0)
lift(h, 0)
c = planner.generate_constraints("cube", 0, action="target", hand_name=h)
_, pose = planner.generate_end_effector_pose(c, hand_name=h)
planner.move_to_pose_with_screw(pose, h)
planner.open_hand(h)
planner.move_to_pose_with_screw(init_pose(h), h)

# step: cubes 1 and 2, each on the one below
for below, oid in [(0, 1), (1, 2)]:
    h = hand_for("cube", oid)
    pinch(h, oid)
    lift(h, oid)
    c = planner.generate_constraints("cube", oid, action="move", hand_name=h, relative_obj_name="cube",
                                     relative_obj_id=below, relative_p=[0.0, 0.0, 0.045])
    _, pose = planner.generate_end_effector_pose(c, hand_name=h)
    planner.move_to_pose_with_screw(pose, h)
    planner.open_hand(h)
    planner.move_to_pose_with_screw(init_pose(h), h)
