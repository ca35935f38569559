# task coverage: two hands on one object: the left hand at grip_left, the right at grip_right (point=), both
# moving at once; then both lift the pot to its target (10 cm up) together, the pot attached to both hands.
# style: the paper's `def step(planner):` with `# Step N:` comments and list arguments.
def step(planner):
    # Step 1: Both hands pre-grasp and go to the pot's grips at the same time
    planner.hand_pre_grasp("all")
    cl = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="left", point="grip_left")
    cr = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="right", point="grip_right")
    _, pl = planner.generate_end_effector_pose(cl, hand_name="left")
    _, pr = planner.generate_end_effector_pose(cr, hand_name="right")
    planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[False, False])
    # Step 2: Close both hands on the grips
    planner.hand_grasp("left", grasp_object="pot", obj_id=0)
    planner.hand_grasp("right", grasp_object="pot", obj_id=0)
    # Step 3: Lift the pot 10 cm, level
    cl = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="left")
    cr = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="right")
    _, pl = planner.generate_end_effector_pose(cl, hand_name="left")
    _, pr = planner.generate_end_effector_pose(cr, hand_name="right")
    planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[True, True], object_name=["pot", "pot"],
                                    object_id=[0, 0])
