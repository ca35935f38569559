from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand grasps the drawer
    planner.hand_pre_grasp("left")
    constraint_r = planner.generate_constraints(
            obj_name="drawer",
            obj_id=0,
            action="grasp",
            hand_name="left"
        )
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "left")
    planner.move_to_pose_with_screw(
        target_effector_pose,
        "left",
        attach_obj=False
    )
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: Left hand opens the drawer to an openness of 1
    constraint_open = planner.generate_constraints(
        obj_name="drawer",
        obj_id=0,
        action="grasp",
        hand_name="left",
        openness=1
    )
    _, target_open_pose = planner.generate_end_effector_pose(constraint_open, "left")
    planner.move_to_pose_with_screw(
        target_open_pose,
        "left",
        attach_obj=True,
        object_name="drawer",
        object_id=0
    )
    # Step 3: Left hand releases the drawer
    planner.open_hand("left")
