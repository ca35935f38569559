# No regrasp: pinch the edge and lift the screen all the way (0.3 -> 0.6 -> 0.85) in one hold.
def step(planner):
    planner.hand_pre_pinch("right")
    cons = planner.generate_constraints("laptop", 0, "pinch", "right")
    _, pose = planner.generate_end_effector_pose(cons, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", "laptop", 0)
    for o in [0.3, 0.6, 0.85]:
        cons = planner.generate_constraints("laptop", 0, "pinch", "right", openness=o)
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
