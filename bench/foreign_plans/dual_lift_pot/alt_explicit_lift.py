# Both hands take the pot's handles together; then the lift is written out as constraints: for each hand the
# pot's centre goes 8 cm straight up and the pot's z axis stays vertical, so both hands aim at the same pot pose.
def step(planner):
    env = planner.env
    planner.hand_pre_grasp("all")
    poses = []
    for hand in ("left", "right"):
        c = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name=hand)
        _, pose = planner.generate_end_effector_pose(c, hand_name=hand)
        poses.append(pose)
    planner.move_to_pose_with_screw(poses, "all", attach_obj=[False, False])
    planner.hand_grasp("all", grasp_object="pot", obj_id=0)

    centre = get_point_in_env(env, type_name="pot", obj_id=0)
    up = np.array([0.0, 0.0, 1.0])
    poses = []
    for hand, frame in (("left", "l_hand_base_link"), ("right", "r_hand_base_link")):
        lift = [
            Constraint(env=env, type="point2point", end_effector_frame=frame,
                       hand_key_point=centre, object_key_point=centre + np.array([0.0, 0.0, 0.08])),
            Constraint(env=env, type="parallel", end_effector_frame=frame,
                       hand_axis=get_axis_in_env(env, "z", obj_type="pot", obj_id=0), object_axis=up),
        ]
        _, pose = planner.generate_end_effector_pose(lift, hand_name=hand)
        poses.append(pose)
    planner.move_to_pose_with_screw(poses, "all", attach_obj=[True, True], object_name=["pot", "pot"],
                                    object_id=[0, 0])
