# task coverage (a lid raised with one hold, then flipped): the right hand pinches the shut screen's top edge
# (pinch@screen_edge), lifts it to openness 0.55 holding it, lets go, gets under the edge (target1) and flips
# it fully up (target2).
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Pinch the screen's top edge
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="laptop", obj_id=0)
    # Step 2: Lift the screen to about half open
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right", openness=0.55)
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Release and get under the screen
    planner.open_hand("right")
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    # Step 4: Flip it fully up
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
