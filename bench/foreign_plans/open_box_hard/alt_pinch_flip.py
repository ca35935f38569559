# Pinch (not grasp) the tab to lift the lid to 0.6, then flip it from under with target1/target2;
# if the flip cannot be planned, pinch again and lift it the rest of the way.
def step(planner):
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="box", obj_id=0)
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right", openness=0.6)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
    planner.open_hand("right")
    try:
        for action in ["target1", "target2"]:
            c = planner.generate_constraints(obj_name="box", obj_id=0, action=action, hand_name="right")
            _, pose = planner.generate_end_effector_pose(c, "right")
            planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    except Exception as e:
        print("flip failed:", e)
        planner.hand_pre_pinch("right")
        c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right")
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
        planner.hand_pinch("right", pinch_object="box", obj_id=0)
        c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right", openness=0.95)
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
        planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
