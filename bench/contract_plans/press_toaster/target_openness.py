# verb: press (item 3), through the prompt's own words for articulated parts: "target1" / "target2" put "the
# fingertip on its first / second push or flip point (with `openness`: pushing the part to that openness)".
# The author treats the lever like a part pushed down: target1 on the lever, target2 with openness=1.0.
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Extend the right index finger, other fingers curled
    planner.hand_press("right")
    # Step 2: Move the right fingertip onto the toaster lever
    constraint_r = planner.generate_constraints(obj_name="toaster", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 3: Press the lever all the way down
    constraint_r = planner.generate_constraints(obj_name="toaster", obj_id=0, action="target2", hand_name="right",
                                                openness=1.0)
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 4: Return the right hand to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
