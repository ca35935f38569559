# task coverage: the pour action as the API lists it: grasp the cup, carry it to its target (above the bowl's
# near side), action="pour" toward the bowl, then set it back upright (target again) and let go.
# style: the paper's `def step(planner):` with `# Step N:` comments.
def step(planner):
    # Step 1: Right hand grasps the cup
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="cup", obj_id=0)
    # Step 2: Move the cup above and in front of the bowl
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="cup", object_id=0)
    # Step 3: Tilt the cup to pour the cubes into the bowl
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="pour", hand_name="right",
                                     relative_obj_name="bowl", relative_obj_id=0)
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="cup", object_id=0)
    # Step 4: Bring the cup back upright above the bowl's side
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
    _, p = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(p, "right", attach_obj=True, object_name="cup", object_id=0)
