# Grasp the handle and push it shut; if the grasp cannot be planned, push the front with the fingertip instead.
def step(planner):
    try:
        planner.hand_pre_grasp("left")
        c = planner.generate_constraints("drawer", 0, "grasp", "left")
        _, pose = planner.generate_end_effector_pose(c, "left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
        planner.hand_grasp("left", "drawer", 0)
        c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.0)
        _, pose = planner.generate_end_effector_pose(c, "left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
        planner.open_hand("left")
    except Exception as e:
        print("grasp route failed, pushing:", e)
        planner.open_hand("left")
        planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
        planner.hand_press("left")
        for a in ("target1", "target2"):
            c = planner.generate_constraints("drawer", 0, a, "left")
            _, pose = planner.generate_end_effector_pose(c, "left")
            planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
