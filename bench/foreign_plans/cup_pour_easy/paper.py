from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the cup
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="cup", obj_id=0)
    # Step 2: Right hand lifts the cup
    constraint_r = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="cup", object_id=0)
    # Step 3: Right hand moves the cup above and in front of the bowl
    constraint_r = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                                relative_obj_name="bowl", relative_obj_id=0,
                                                relative_p=np.array([0, -0.06, 0.13]))
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="cup", object_id=0)
    # Step 4: Right hand tilts the cup to pour its contents into the bowl
    constraints = []
    constraints.append(
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="cup", obj_id=0),
            object_key_point=get_point_in_env(planner.env, type_name="bowl", obj_id=0) + np.array([0, -0.05, 0.13]),
        )
    )
    constraints.append(
        Constraint(
            env=planner.env,
            type="parallel",
            end_effector_frame="r_hand_base_link",
            hand_axis=get_axis_in_env(planner.env, axis_name="opening", obj_type="cup", obj_id=0),
            object_axis=np.array([0, 0.8, -0.6]),
        )
    )
    _, target_effector_pose = planner.generate_end_effector_pose(constraints, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="cup", object_id=0)
