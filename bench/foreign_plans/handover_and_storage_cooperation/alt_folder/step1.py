def step(planner):
    # pull the drawer and bring the block over at the same time; if the two-arm motion cannot be planned,
    # do one arm after the other
    import numpy as np
    _, pl = planner.generate_end_effector_pose(
        planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.9), "left")
    _, pr = planner.generate_end_effector_pose(
        planner.generate_constraints("cube", 0, "move", "right", relative_obj_name="drawer", relative_obj_id=0,
                                     relative_p=np.array([-0.15, -0.18, 0.03])), "right")
    try:
        planner.move_to_pose_with_screw([pl, pr], "all", attach_obj=[True, True],
                                        object_name=["drawer", "cube"], object_id=[0, 0])
    except Exception as e:
        print("together failed:", e)
        planner.move_to_pose_with_screw(pl, "left", attach_obj=True, object_name="drawer", object_id=0)
        planner.move_to_pose_with_screw(pr, "right", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
