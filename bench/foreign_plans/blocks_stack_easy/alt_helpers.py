# One hand after the other, with helper functions defined inside step and numpy imported in it.
def step(planner):
    import numpy as np

    def pinch(hand, obj_id):
        planner.hand_pre_pinch(hand)
        cons = planner.generate_constraints("cube", obj_id, "pinch", hand)
        _, pose = planner.generate_end_effector_pose(cons, hand)
        planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
        planner.hand_pinch(hand, "cube", obj_id)

    def carry_to(hand, obj_id, world_xyz):
        frame = "l_hand_base_link" if hand == "left" else "r_hand_base_link"
        cons = [
            Constraint(env=planner.env, type="point2point", end_effector_frame=frame,
                       hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=obj_id),
                       object_key_point=np.asarray(world_xyz, dtype=float)),
            Constraint(env=planner.env, type="parallel", end_effector_frame=frame,
                       hand_axis=get_axis_in_env(planner.env, axis_name=hand + "_pinch_axis"),
                       object_axis=np.array([0.0, 0.0, -1.0])),
        ]
        _, pose = planner.generate_end_effector_pose(cons, hand)
        planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="cube", object_id=obj_id)

    # the left hand brings cube 0 to the middle of the table
    pinch("left", 0)
    carry_to("left", 0, [-0.33, 0.04, 0.10])
    carry_to("left", 0, [-0.33, 0.04, 0.024])
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

    # the right hand stacks cube 1 on it
    pinch("right", 1)
    top = get_point_in_env(planner.env, type_name="cube", obj_id=0)
    carry_to("right", 1, top + np.array([0.0, 0.0, 0.10]))
    carry_to("right", 1, top + np.array([0.0, 0.0, 0.045]))
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
