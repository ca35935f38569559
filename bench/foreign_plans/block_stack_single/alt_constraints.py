# Explicit Constraint lists in the style of the paper's MCTS sample (no "target"/"move" actions).
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches cube1 from above
    planner.hand_pre_pinch("right")
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, point_name="pinch_point_base_right_hand"),
            object_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=1)
        ),
        Constraint(
            env=planner.env,
            type="parallel",
            end_effector_frame="r_hand_base_link",
            hand_axis=get_axis_in_env(planner.env, axis_name="right_pinch_axis"),
            object_axis=np.array([0, 0, -1])
        )
    ]
    _, target_pose = planner.generate_end_effector_pose(constraints, "right")
    planner.move_to_pose_with_screw(target_pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=1)

    # Step 2: Lift cube1 above cube0
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=1),
            object_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=0) + np.array([0, 0, 0.08])
        ),
        Constraint(
            env=planner.env,
            type="parallel",
            end_effector_frame="r_hand_base_link",
            hand_axis=get_axis_in_env(planner.env, axis_name="right_pinch_axis"),
            object_axis=np.array([0, 0, -1])
        )
    ]
    _, target_pose = planner.generate_end_effector_pose(constraints, "right")
    planner.move_to_pose_with_screw(target_pose, "right", attach_obj=True, object_name="cube", object_id=1)

    # Step 3: Lower cube1 onto cube0 and release it
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=1),
            object_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=0) + np.array([0, 0, 0.045])
        ),
        Constraint(
            env=planner.env,
            type="parallel",
            end_effector_frame="r_hand_base_link",
            hand_axis=get_axis_in_env(planner.env, axis_name="right_pinch_axis"),
            object_axis=np.array([0, 0, -1])
        )
    ]
    _, target_pose = planner.generate_end_effector_pose(constraints, "right")
    planner.move_to_pose_with_screw(target_pose, "right", attach_obj=True, object_name="cube", object_id=1)
    planner.open_hand("right")

    # Step 4: Right hand back to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
