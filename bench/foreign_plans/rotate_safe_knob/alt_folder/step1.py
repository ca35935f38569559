# Turn the knob in two stages: to 0.45 (54 deg), then to 0.8 (96 deg, past the 0.75 the task asks).
def step(planner):
    for o in (0.45, 0.8):
        cons = planner.generate_constraints("safe", 0, "pinch", "right", openness=o, point="knob_fin_right")
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
