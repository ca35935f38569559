# Grasp the handle bar by name (point=), let the hand touch the safe, swing the door in three stages of openness
# (a quarter, a half, all the way), then let go and take the hand home.
def step(planner):
    planner.hand_pre_grasp("right")
    planner.ignore_collision("safe", 0)
    cons = planner.generate_constraints("safe", 0, "grasp", "right", point="handle")
    _, pose = planner.generate_end_effector_pose(cons, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", "safe", 0)
    for o in (0.3, 0.6, 1.0):
        cons = planner.generate_constraints("safe", 0, "grasp", "right", openness=o, point="handle")
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
    planner.open_hand("right")
    planner.restore_collision("safe", 0)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
