# verb: press (item 3). The toaster's only operation is "press@lever_top"; the author asks generate_constraints
# for action="press" (the operation's own name), first at the lever, then with openness=1.0 for the lever all the
# way down, as the prompt shows openness= for the other articulated parts.
# style: our `# step:` blocks, straight from the prompt's worked example.
# step: curl the fingers and extend the right index finger to press
planner.hand_press("right")

# step: bring the right index fingertip onto the top of the toaster's lever
c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: press the lever all the way down (openness 1)
c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right", openness=1.0)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

# step: take the finger off the lever and bring the right hand back
lever = get_point_in_env(planner.env, "lever_top", "toaster", 0)
tip = get_point_in_env(planner.env, "press_point_base_right_hand")
c = [Constraint(planner.env, "point2point", "r_hand_base_link", hand_key_point=tip,
                object_key_point=lever + np.array([0.0, 0.0, 0.06]))]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
