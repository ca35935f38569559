# step: pinch fin
planner.hand_pre_pinch("right")
c = planner.generate_constraints("safe", 0, action="pinch", hand_name="right", point="knob_fin_right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.hand_pinch("right", pinch_object="safe", obj_id=0)
# step: turn
for o in (0.4, 0.75):
    c = planner.generate_constraints("safe", 0, action="pinch", hand_name="right", point="knob_fin_right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    print(planner.events[-2:])
