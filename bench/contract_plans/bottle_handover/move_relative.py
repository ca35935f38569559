# verb: grasp-to-grasp hand-over of a round body (item 3), on a new task spec (tasks/bottle_handover.yaml),
# without the hand-over target: the right hand lifts the bottle 8 cm with action="move" (relative to the
# bottle itself), then moves it 19 cm to the left (toward the middle) the same way; the left hand grasps it
# there, the right lets go, and the left puts it on target2 (the spot on the table on the left).
# style: the paper's `def step(planner):` with `# Step N:` comments; relative_p in world metres.
def step(planner):
    # Step 1: Right hand grasps bottle 0
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="bottle", obj_id=0)
    # Step 2: Lift the bottle 8 cm
    c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="bottle", relative_obj_id=0, relative_p=np.array([0, 0, 0.08]))
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="bottle", object_id=0)
    # Step 3: Bring it toward the middle, between the hands
    c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="bottle", relative_obj_id=0, relative_p=np.array([0.02, 0.19, 0.0]))
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="bottle", object_id=0)
    # Step 4: Left hand takes the bottle
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
    # Step 5: Right hand releases and goes back
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
    # Step 6: Left hand puts the bottle down on the left
    c = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target2", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="bottle", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
