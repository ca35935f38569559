# Pick the upper handle grip explicitly (point=), let the hand touch the cabinet, and pull in two stages.
def step(planner):
    # Step 1: grasp the upper part of the handle
    planner.hand_pre_grasp("left")
    planner.ignore_collision("drawer", 0)
    cons = planner.generate_constraints("drawer", 0, "grasp", "left", point="handle_upper")
    _, pose = planner.generate_end_effector_pose(cons, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", "drawer", 0)
    # Step 2: pull to half, then all the way
    for o in (0.5, 1.0):
        cons = planner.generate_constraints("drawer", 0, "grasp", "left", openness=o, point="handle_upper")
        _, pose = planner.generate_end_effector_pose(cons, "left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 3: let go and go home
    planner.open_hand("left")
    planner.restore_collision("drawer", 0)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
