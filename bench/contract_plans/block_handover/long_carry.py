# verb: carrying a pinched object through a long move (item 3): the right hand pinches the block, lifts it
# 15 cm, carries it to the mid-air hand-over target; the left hand pinches the free end, the right lets go, the
# left lifts it 5 cm more and carries it across to the target cube (its own target) and lets go.
# style: the paper's `def step(planner):` with `# Step N:` comments; aliases ("rectangular_cube", "target_cube").
def step(planner):
    # Step 1: Right hand pinches the rectangular cube
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="rectangular_cube", obj_id=0)
    # Step 2: Lift it 15 cm
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="rectangular_cube", relative_obj_id=0,
                                     relative_p=np.array([0, 0, 0.15]))
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="rectangular_cube", object_id=0)
    # Step 3: Carry it to the hand-over pose
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="rectangular_cube", object_id=0)
    # Step 4: Left hand pinches the block's free end
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="rectangular_cube", obj_id=0)
    # Step 5: Right hand releases and goes home
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
    # Step 6: Left hand lifts the block a little and carries it onto the target cube
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="move", hand_name="left",
                                     relative_obj_name="target_cube", relative_obj_id=0,
                                     relative_p=np.array([0, 0, 0.15]))
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="rectangular_cube", object_id=0)
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="rectangular_cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
