from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches cube1
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(
        obj_name="cube",
        obj_id=1,
        action="pinch",
        hand_name="right"
    )
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(
        target_effector_pose,
        "right",
        attach_obj=False
    )
    planner.hand_pinch("right", pinch_object="cube", obj_id=1)
    # Step 2: Right hand lifts cube1 to the target pose
    constraint_lift = planner.generate_constraints(
        obj_name="cube",
        obj_id=1,
        action="target",
        hand_name="right"
    )
    _, target_lift_pose = planner.generate_end_effector_pose(constraint_lift, "right")
    planner.move_to_pose_with_screw(
        target_lift_pose,
        "right",
        attach_obj=True,
        object_name="cube",
        object_id=1
    )
    # Step 3: Right hand moves cube1 to just above cube0
    constraint_move = planner.generate_constraints(
        obj_name="cube",
        obj_id=1,
        action="move",
        hand_name="right",
        relative_obj_name="cube",
        relative_obj_id=0,
        relative_p=np.array([0, 0, 0.045])
    )
    _, target_move_pose = planner.generate_end_effector_pose(constraint_move, "right")
    planner.move_to_pose_with_screw(
        target_move_pose,
        "right",
        attach_obj=True,
        object_name="cube",
        object_id=1
    )
    # Step 4: Right hand releases cube1
    planner.open_hand("right")
    # Step 5: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
