# Pinch the fin's right end by name (the pinch the right hand comes to palm down).
def step(planner):
    planner.hand_pre_pinch("right")
    cons = planner.generate_constraints("safe", 0, "pinch", "right", point="knob_fin_right")
    _, pose = planner.generate_end_effector_pose(cons, "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_pinch("right", "safe", 0)
