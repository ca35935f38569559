# verb: the knob pinch as the task words it (item 3): "thumb under it, index on top, palm down". The author
# extends generate_constraints' list with the hand's thumb-to-index axis along the fin's normal (up at knob 0:
# from the thumb below to the index above), then turns by 90 deg (openness 0.75) holding the fin.
# rule probes: generate_constraints returns a list that may be extended; hand axes named in the prompt.
# style: our `# step:` blocks.
# step: open thumb and index to pinch
planner.hand_pre_pinch("right")

# step: pinch the fin with the thumb under it and the index on top
env = planner.env
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right")
thumb_to_index = get_axis_in_env(env, "right_thumb_2_index")
fin_up = get_axis_in_env(env, "fin_normal", "safe", 0)
c = list(c) + [Constraint(env, "angle", "r_hand_base_link", hand_axis=thumb_to_index, object_axis=fin_up,
                          lower=0.0, upper=math.radians(20))]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="safe", obj_id=0)

# step: turn the knob 90 degrees clockwise
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", openness=90 / 120)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)

# step: let go and take the right hand home
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
