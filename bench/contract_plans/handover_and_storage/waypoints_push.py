# verb: carrying a pinched object through a long move (item 3) via explicit waypoints: the right hand lifts the
# pinched block 12 cm straight up before carrying it to target1 (the mid-air hand-over); the left hand, after
# taking it, lifts it 6 cm (move relative to the block itself) before carrying it to target2 above the drawer.
# The drawer is opened by a grasp pulled to openness 0.9 and shut with its push targets (target1/target2).
# style: the paper's `def step(planner):` with `# Step N:` comments, named targets throughout.
def step(planner):
    # Step 1: Left hand opens the drawer to 0.9
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.9)
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="drawer", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
    # Step 2: Right hand pinches the block and lifts it
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="rectangular_cube", obj_id=0)
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.12]))
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="cube", object_id=0)
    # Step 3: Right hand carries it to the hand-over pose (target1)
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target1", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="cube", object_id=0)
    # Step 4: Left hand takes it; right hand releases and goes back
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="cube", obj_id=0)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
    # Step 5: Left hand lifts the block a little, carries it over the drawer (target2) and drops it in
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                     relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.06]))
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="cube", object_id=0)
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target2", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    # Step 6: Left index fingertip pushes the drawer shut
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target2", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
