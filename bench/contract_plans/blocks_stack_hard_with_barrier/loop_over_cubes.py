# rule: constructs the prompt allows (item 1): a helper function, a for loop over (cube, hand, base) tuples,
# a dict, f-strings and print. Cube 0 goes to its target by the hand on its side; cubes 1 and 2 are stacked by
# the right hand, each lifted 10 cm first so that it clears the walls and the platform.
# style: one `# step:` block per cube, the helper defined once per step.
# step: left hand puts cube 0 on the stacking spot
def pick_and_place(obj_id, hand, base_id):
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="pinch", hand_name=hand)
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=False)
    planner.hand_pinch(hand, pinch_object="cube", obj_id=obj_id)
    c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="move", hand_name=hand,
                                     relative_obj_name="cube", relative_obj_id=obj_id, relative_p=np.array([0, 0, 0.10]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=obj_id)
    if base_id is None:
        c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="target", hand_name=hand)
    else:
        c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="move", hand_name=hand,
                                         relative_obj_name="cube", relative_obj_id=base_id,
                                         relative_p=np.array([0, 0, 0.045]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=obj_id)
    planner.open_hand(hand)
    home = {"left": planner.left_hand_init_pose, "right": planner.right_hand_init_pose}[hand]
    planner.move_to_pose_with_screw(home, hand)
    print(f"cube {obj_id} placed by the {hand} hand")

for obj_id, hand, base in [(0, "left", None)]:
    pick_and_place(obj_id, hand, base)

# step: right hand stacks cube 1 on cube 0, then cube 2 on cube 1
def pick_and_place(obj_id, hand, base_id):
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="pinch", hand_name=hand)
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=False)
    planner.hand_pinch(hand, pinch_object="cube", obj_id=obj_id)
    c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="move", hand_name=hand,
                                     relative_obj_name="cube", relative_obj_id=obj_id, relative_p=np.array([0, 0, 0.10]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=obj_id)
    c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="move", hand_name=hand,
                                     relative_obj_name="cube", relative_obj_id=base_id,
                                     relative_p=np.array([0, 0, 0.045]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=obj_id)
    planner.open_hand(hand)
    print(f"cube {obj_id} stacked on cube {base_id}")

for obj_id, base in [(1, 0), (2, 1)]:
    pick_and_place(obj_id, "right", base)
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
