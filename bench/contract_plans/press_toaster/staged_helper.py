# verb: press (item 3) in stages: a helper function (allowed: the prompt forbids only while/try/with/lambda/class)
# puts the right fingertip on the lever's top where it will be at each openness in a for loop, 0.25 .. 1.0,
# with the press axis held down, then lifts off.
# style: helper defined and used inside one step; loops; the press point from the hand's annotated points.
# step: ready the right index finger
planner.hand_press("right")

# step: press the lever down in four stages
def fingertip_on_lever(openness, lift):
    env = planner.env
    target = get_point_in_env(env, "lever_top", "toaster", 0, openness=openness) + np.array([0.0, 0.0, lift])
    tip = get_point_in_env(env, "press_point_base_right_hand")
    axis = get_axis_in_env(env, "right_press_axis")
    cons = [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=target),
            Constraint(env, "parallel", "r_hand_base_link", hand_axis=axis, object_axis=np.array([0.0, 0.0, -1.0]))]
    _, pose = planner.generate_end_effector_pose(cons, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

fingertip_on_lever(0.0, 0.015)
for o in [0.25, 0.5, 0.75, 1.0]:
    fingertip_on_lever(o, -0.004)

# step: lift the finger off the lever and take the right hand back
tip = get_point_in_env(planner.env, "press_point_base_right_hand")
c = [Constraint(planner.env, "point2point", "r_hand_base_link", hand_key_point=tip, object_key_point=tip + np.array([-0.03, 0.0, 0.08]))]
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
