# The tall narrow-necked bottle (bottle 1) is pinched at its neck (pinch@neck) instead of grasped;
# the lift goes to a world height ("move" is not needed), both hands at once.
def step(planner):
    # Step 1: hand postures
    planner.hand_pre_grasp("left")
    planner.hand_pre_pinch("right")
    # Step 2: both hands to their holds at once
    cl = planner.generate_constraints("bottle", 0, "grasp", "left")
    cr = planner.generate_constraints("bottle", 1, "pinch", "right")
    _, pl = planner.generate_end_effector_pose(cl, "left")
    _, pr = planner.generate_end_effector_pose(cr, "right")
    planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[False, False])
    planner.hand_grasp("left", "bottle", 0)
    planner.hand_pinch("right", "bottle", 1)
    # Step 3: lift both 8 cm
    env = planner.env
    goals = []
    for hand, frame, i in (("left", "l_hand_base_link", 0), ("right", "r_hand_base_link", 1)):
        p = get_point_in_env(env, type_name="bottle", obj_id=i)
        cons = [Constraint(env=env, type="point2point", end_effector_frame=frame,
                           hand_key_point=p, object_key_point=p + np.array([0.0, 0.0, 0.08]))]
        goals.append(planner.generate_end_effector_pose(cons, hand)[1])
    planner.move_to_pose_with_screw(goals, "all", attach_obj=[True, True], object_name=["bottle", "bottle"],
                                    object_id=[0, 1])
