# rule probe (item 1): try/except. The prompt forbids `try`; an LLM guarding against a failed pinch writes
# try/except Exception and falls back to a grasp of the cube's top (the family annotates grasp@top). Order as
# the paper: left pinches cube 0, right pinches cube 1, at once; left puts cube 0 on its target; right puts
# cube 1 on cube 0; right takes cube 2 and puts it on cube 1.
# style: the paper's `def step(planner):`, a helper with try/except inside it.
def step(planner):
    def take(hand, obj_id):
        try:
            planner.hand_pre_pinch(hand)
            c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="pinch", hand_name=hand)
            _, p = planner.generate_end_effector_pose(c, hand_name=hand)
            planner.move_to_pose_with_screw(p, hand, attach_obj=False)
            planner.hand_pinch(hand, pinch_object="cube", obj_id=obj_id)
        except Exception as exc:
            print("pinch failed, grasping instead:", exc)
            planner.open_hand(hand)
            planner.hand_pre_grasp(hand)
            c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="grasp", hand_name=hand)
            _, p = planner.generate_end_effector_pose(c, hand_name=hand)
            planner.move_to_pose_with_screw(p, hand, attach_obj=False)
            planner.hand_grasp(hand, grasp_object="cube", obj_id=obj_id)

    def put(hand, obj_id, on_id=None):
        if on_id is None:
            c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="target", hand_name=hand)
        else:
            c = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action="move", hand_name=hand,
                                             relative_obj_name="cube", relative_obj_id=on_id,
                                             relative_p=np.array([0, 0, 0.045]))
        _, p = planner.generate_end_effector_pose(c, hand_name=hand)
        planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=obj_id)
        planner.open_hand(hand)

    # Step 1: Left hand takes cube 0, right hand takes cube 1
    take("left", 0)
    take("right", 1)
    # Step 2: Left hand puts cube 0 at the target place and goes home
    put("left", 0)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
    # Step 3: Right hand puts cube 1 above cube 0
    put("right", 1, on_id=0)
    # Step 4: Right hand picks up cube 2 and puts it above cube 1
    take("right", 2)
    put("right", 2, on_id=1)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, hand_name="right")
