# A user's plan: press the lid with the extended index fingertip, moving through hand-picked points
# computed from the lid's annotated front point at decreasing openness (explicit Constraints + path loop).
def step(planner):
    import numpy as np
    env = planner.env
    planner.hand_press("right")
    planner.ignore_collision("box", 0)
    now = get_point_in_env(env, "lid_front", "box", 0)
    # start 4 cm above the tab, then follow where the tab will be as the lid goes down
    waypoints = [now + np.array([0.0, 0.0, 0.04])]
    for o in (0.35, 0.2, 0.05, 0.0):
        waypoints.append(get_point_in_env(env, "lid_front", "box", 0, openness=o) + np.array([0.0, 0.0, 0.01]))
    for wp in waypoints:
        cons = [
            Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                       hand_key_point=get_point_in_env(env, point_name="press_point_base_right_hand"),
                       object_key_point=wp),
            Const(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                  hand_axis=get_axis_in_env(env, axis_name="right_press_axis"),
                  object_axis=np.array([0.0, 0.0, -1.0])),
        ]
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.restore_collision("box", 0)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
