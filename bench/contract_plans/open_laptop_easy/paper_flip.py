# task coverage: the paper's open_laptop_easy description ("moves to be under the laptop screen, then moves to
# flip the laptop screen up") with the prompt's target1/target2, in the paper's own format.
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Right hand moves under the laptop screen
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 2: Right hand flips the screen up
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 3: Return
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
