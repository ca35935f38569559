# verb: lowering a lid in stages with one hold (item 3): a pinch on the lid's tab (the family annotates
# pinch@lid_front too), lowered through np.linspace(0.65, 0.25, 5) with the pinch kept, then released so the
# lid falls shut ("falls shut when let go low", the model's description); pushed with target1/target2 only if
# it is not shut yet (an if on the lid's openness is not available to a plan, so the push always runs).
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Pinch the lid's tab with the right hand
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="box", obj_id=0)
    # Step 2: Bring the lid down in five stages while pinching it
    for o in np.linspace(0.65, 0.25, 5):
        c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right",
                                         openness=float(o))
        _, p = planner.generate_end_effector_pose(c, hand_name="right")
        planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="box", object_id=0)
    # Step 3: Release the lid
    planner.open_hand("right")
    # Step 4: Push it fully closed
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
