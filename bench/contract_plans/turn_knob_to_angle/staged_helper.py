# verb: turn a knob to a given angle (item 3) in 20-degree stages with one pinch, on a new task spec
# (tasks/turn_knob_to_angle.yaml): a helper turn_to(deg) converts degrees to the knob's openness and follows the
# fin; called for 20, 40, 60 deg.
# style: helper function and a for loop inside a step (constructs the prompt allows).
# step: pinch the knob fin
planner.hand_pre_pinch("right")
c = planner.generate_constraints("safe", 0, "pinch", "right", point="knob_fin_right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="safe", obj_id=0)

# step: turn the knob to 60 degrees in three stages
def turn_to(deg):
    openness = min(max(deg / 120.0, 0.0), 1.0)
    cons = planner.generate_constraints("safe", 0, "pinch", "right", openness=openness)
    _, p = planner.generate_end_effector_pose(cons, "right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="safe", object_id=0)

for target_deg in range(20, 61, 20):
    turn_to(target_deg)

# step: release and go home
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
