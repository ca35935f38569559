from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the handle of the safe door
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(
            obj_name="safe",
            obj_id=0,
            action="grasp",
            hand_name="right"
        )
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(
        target_effector_pose,
        "right",
        attach_obj=False
    )
    planner.hand_grasp("right", grasp_object="safe", obj_id=0)
    # Step 2: Right hand pulls the safe door open to an openness of 0.9
    constraint_open = planner.generate_constraints(
        obj_name="safe",
        obj_id=0,
        action="grasp",
        hand_name="right",
        openness=0.9
    )
    _, target_open_pose = planner.generate_end_effector_pose(constraint_open, "right")
    planner.move_to_pose_with_screw(
        target_open_pose,
        "right",
        attach_obj=True,
        object_name="safe",
        object_id=0
    )
    # Step 3: Right hand releases the safe door
    planner.open_hand("right")
