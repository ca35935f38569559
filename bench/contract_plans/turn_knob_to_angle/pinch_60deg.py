# verb: turn a knob to a given angle with a pinch (item 3), on a new task spec (tasks/turn_knob_to_angle.yaml,
# the larger safe, 60 deg clockwise = knob openness 0.5): pinch the fin, one move to openness 60/120 holding it,
# let go.
# style: our `# step:` blocks, straight from the worked example.
# step: pinch the knob's fin with the right hand
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="safe", obj_id=0)

# step: turn it 60 deg clockwise (the knob turns 120 deg at openness 1)
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", openness=60 / 120)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)

# step: let go of the knob and move the hand back
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
