# Press on the back of the screen (push@screen_back) with the palm facing down, following where that point
# will be at lower openness: explicit constraints, helper function, numpy imported inside the step.
def step(planner):
    import numpy as np

    def press_at(point):
        cons = [
            Constraint(env=planner.env, type="point2point", end_effector_frame="r_hand_base_link",
                       hand_key_point=get_point_in_env(planner.env, point_name="palm_center_right_hand"),
                       object_key_point=point),
            Constraint(env=planner.env, type="parallel", end_effector_frame="r_hand_base_link",
                       hand_axis=get_axis_in_env(planner.env, axis_name="right_grasp_axis"),
                       object_axis=np.array([0.0, 0.0, -1.0])),
        ]
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

    planner.ignore_collision("laptop", 0)
    press_at(get_point_in_env(planner.env, "screen_back", "laptop", 0) + np.array([0.0, 0.0, 0.05]))
    for o in (0.3, 0.1, 0.0):
        press_at(get_point_in_env(planner.env, "screen_back", "laptop", 0, openness=o) + np.array([0.0, 0.0, 0.015]))
    planner.restore_collision("laptop", 0)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
