# The right hand lays the first base cube at a fixed spot, the left hand sets cube0 beside it (relative_p),
# and cube2 goes on the midpoint of the two measured base cubes (explicit Constraint). Loops over approach heights.
def step(planner):
    import numpy as np

    def grab(hand, i):
        planner.hand_pre_pinch(hand)
        c = planner.generate_constraints(obj_name="cube", obj_id=i, action="pinch", hand_name=hand)
        _, p = planner.generate_end_effector_pose(c, hand_name=hand)
        planner.move_to_pose_with_screw(p, hand, attach_obj=False)
        planner.hand_pinch(hand, pinch_object="cube", obj_id=i)

    def put(hand, i, goal):
        frame = {"left": "l_hand_base_link", "right": "r_hand_base_link"}[hand]
        for lift in (0.08, 0.0):
            cons = [
                Constraint(env=planner.env, type="point2point", end_effector_frame=frame,
                           hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=i),
                           object_key_point=goal + np.array([0.0, 0.0, lift])),
                Constraint(env=planner.env, type="parallel", end_effector_frame=frame,
                           hand_axis=get_axis_in_env(planner.env, axis_name=f"{hand}_pinch_axis"),
                           object_axis=np.array([0.0, 0.0, -1.0])),
            ]
            _, p = planner.generate_end_effector_pose(cons, hand_name=hand)
            planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=i)
        planner.open_hand(hand)

    # cube1 (right of the pair) at y = -0.005
    grab("right", 1)
    put("right", 1, np.array([-0.33, -0.005, 0.023]))
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

    # cube0 4.5 cm to its left, placed relative to cube1
    grab("left", 0)
    c = planner.generate_constraints("cube", 0, "move", "left", relative_obj_name="cube", relative_obj_id=1,
                                     relative_p=np.array([0.0, 0.045, 0.06]))
    _, p = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="cube", object_id=0)
    c = planner.generate_constraints("cube", 0, "move", "left", relative_obj_name="cube", relative_obj_id=1,
                                     relative_p=np.array([0.0, 0.045, 0.003]))
    _, p = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

    # cube2 across both
    grab("right", 2)
    mid = 0.5 * (get_point_in_env(planner.env, type_name="cube", obj_id=0)
                 + get_point_in_env(planner.env, type_name="cube", obj_id=1))
    put("right", 2, mid + np.array([0.0, 0.0, 0.044]))
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
