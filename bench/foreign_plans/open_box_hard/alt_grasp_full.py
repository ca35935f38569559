# One continuous turn: grasp the tab and carry the lid past upright (openness 0.95) without regrasping.
def step(planner):
    # Step 1: grasp the lid tab
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("box", 0, "grasp", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", "box", 0)
    # Step 2: turn it open in three stages
    for o in (0.3, 0.6, 0.95):
        c = planner.generate_constraints("box", 0, "grasp", "right", openness=o)
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
    # Step 3: let go
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
