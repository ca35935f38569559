# verb: turn a knob by an angle with one pinch (item 3), in stages of 30 deg: a for loop over 30, 60, 90 deg,
# each converted to the knob's openness (deg / 120) and followed with the fin held; a few degrees extra at the
# end (95) so that the knob does not stop short of 90.
# style: our `# step:` blocks, a for loop, math.radians-free degree bookkeeping.
# step: pre-pinch the right hand
planner.hand_pre_pinch("right")

# step: pinch the knob's fin with the right hand, thumb and index on its two faces
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", point="knob_fin_right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="safe", obj_id=0)

# step: turn the knob clockwise 30 deg at a time, keeping the pinch
KNOB_MAX_DEG = 120.0
for deg in [30, 60, 95]:
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right",
                                     openness=deg / KNOB_MAX_DEG)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)

# step: release the fin and bring the right hand back
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
