# Grasp and close all the way in small openness steps (a loop), with a fallback: if a step of the turn
# cannot be solved, release and push the lid down with target1/target2.
def step(planner):
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("box", 0, "grasp", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", "box", 0)
    try:
        for o in [0.55, 0.35, 0.15, 0.0]:
            c = planner.generate_constraints("box", 0, "grasp", "right", openness=o)
            _, pose = planner.generate_end_effector_pose(c, "right")
            planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
        planner.open_hand("right")
    except Exception as err:
        print("turning failed:", err)
        planner.open_hand("right")
        for action in ("target1", "target2"):
            c = planner.generate_constraints("box", 0, action, "right")
            _, pose = planner.generate_end_effector_pose(c, "right")
            planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
