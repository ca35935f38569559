# One hand after the other, each lifting 8 cm with an explicit point constraint that keeps the bottle upright.
def step(planner):
    env = planner.env
    for hand, i in (("left", 0), ("right", 1)):
        frame = "l_hand_base_link" if hand == "left" else "r_hand_base_link"
        planner.hand_pre_grasp(hand)
        c = planner.generate_constraints(obj_name="bottle", obj_id=i, action="grasp", hand_name=hand)
        _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
        planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
        planner.hand_grasp(hand, grasp_object="bottle", obj_id=i)
        here = get_point_in_env(env, type_name="bottle", obj_id=i)
        lift = [
            Constraint(env=env, type="point2point", end_effector_frame=frame,
                       hand_key_point=here, object_key_point=here + np.array([0.0, 0.0, 0.08])),
            Constraint(env=env, type="parallel", end_effector_frame=frame,
                       hand_axis=get_axis_in_env(env, "z", obj_type="bottle", obj_id=i),
                       object_axis=np.array([0.0, 0.0, 1.0])),
        ]
        _, pose = planner.generate_end_effector_pose(lift, hand_name=hand)
        planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="bottle", object_id=i)
