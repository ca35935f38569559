# verb: lowering a lid in stages with one hold (item 3): the paper's close_laptop_hard description literally,
# with the screen brought down in two stages (0.5, then 0.3) by the same grasp, then "releases the laptop
# screen and moves above it" (target1), then "flip the laptop screen fully down" (target2).
# style: the paper's `def step(planner):` with `# Step N:` comments and its variable names.
def step(planner):
    # Step 1: Right hand grasps the laptop screen from above
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="laptop", obj_id=0)
    # Step 2: Adjust the screen's openness to 0.5, then 0.3, keeping the grasp
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right",
                                                openness=0.5)
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right",
                                                openness=0.3)
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Release the screen and move above it
    planner.open_hand("right")
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 4: Flip the screen fully down
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
