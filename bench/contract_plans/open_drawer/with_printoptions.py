# rule probe (item 1): with. The prompt forbids `with`; an LLM printing positions for its own log writes
# `with np.printoptions(...)`. The plan: grasp the drawer handle with the left hand, pull to openness 0.5 then
# 1.0 holding it, release, go home.
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Left hand grasps the drawer handle
    handle = get_point_in_env(planner.env, "handle", "drawer", 0)
    with np.printoptions(precision=3, suppress=True):
        print("drawer handle at", handle)
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
    _, p = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(p, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: Pull the drawer out in two stages to an openness of 1
    for o in [0.5, 1.0]:
        c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=o)
        _, p = planner.generate_end_effector_pose(c, hand_name="left")
        planner.move_to_pose_with_screw(p, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 3: Release the handle and go back
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
