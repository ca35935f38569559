# YAML names (cube 0); the handover point is relative to the drawer (relative_p); the block is dropped with a
# "move" relative to the drawer's storage point computed by hand; the drawer is pushed shut (target1/target2)
# rather than pulled by the handle.
def step(planner):
    import numpy as np
    env = planner.env

    def go(hand, cons, carrying=None):
        _, pose = planner.generate_end_effector_pose(cons, hand)
        if carrying is None:
            planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
        else:
            planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name=carrying[0], object_id=carrying[1])

    # Step 1: open the drawer with the left hand
    planner.hand_pre_grasp("left")
    go("left", planner.generate_constraints("drawer", 0, "grasp", "left"))
    planner.hand_grasp("left", "drawer", 0)
    go("left", planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.9), ("drawer", 0))
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

    # Step 2: right hand brings the block to a point 20 cm right of and 5 cm above the drawer's centre
    planner.hand_pre_pinch("right")
    go("right", planner.generate_constraints("cube", 0, "pinch", "right"))
    planner.hand_pinch("right", "cube", 0)
    go("right", planner.generate_constraints("cube", 0, "target", "right"), ("cube", 0))
    go("right", planner.generate_constraints("cube", 0, "move", "right", relative_obj_name="drawer",
                                              relative_obj_id=0, relative_p=np.array([-0.14, -0.18, 0.03])),
       ("cube", 0))

    # Step 3: left hand grasps the block's top and the right hand lets go
    planner.hand_pre_grasp("left")
    go("left", planner.generate_constraints("cube", 0, "grasp", "left"))
    planner.hand_grasp("left", "cube", 0)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

    # Step 4: drop it into the drawer
    storage = get_point_in_env(env, "storage", "drawer", 0)
    go("left", [Constraint(env=env, type="point2point", end_effector_frame="l_hand_base_link",
                           hand_key_point=get_point_in_env(env, type_name="cube", obj_id=0),
                           object_key_point=storage + np.array([0.0, 0.0, 0.08]))], ("cube", 0))
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

    # Step 5: push the drawer shut
    for a in ("target1", "target2"):
        go("left", planner.generate_constraints("drawer", 0, a, "left"))
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
