from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand pinches cube0 and right hand pinches cube1 simultaneously
    planner.hand_pre_pinch("all")
    constraint_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all", attach_obj=[False, False])
    planner.hand_pinch("left", pinch_object="cube", obj_id=0)
    planner.hand_pinch("right", pinch_object="cube", obj_id=1)
    # Step 2: Both hands lift their cubes
    constraint_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all",
                                    attach_obj=[True, True], object_name=["cube", "cube"], object_id=[0, 1])
    # Step 3: Left hand moves cube0 to the target position and releases it
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="l_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=0),
            object_key_point=np.array([-0.33, 0.04, 0.025]),
        ),
        Constraint(
            env=planner.env,
            type="parallel",
            end_effector_frame="l_hand_base_link",
            hand_axis=get_axis_in_env(planner.env, axis_name="left_pinch_axis"),
            object_axis=np.array([0, 0, -1]),
        ),
    ]
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraints, hand_name="left")
    planner.move_to_pose_with_screw(target_effector_pose_l, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
    # Step 4: Right hand moves cube1 to the right side of cube0 and releases it
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=0,
                                                relative_p=np.array([0, -0.045, 0.003]))
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True, object_name="cube", object_id=1)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
    # Step 5: Right hand pinches cube2
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="pinch", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=2)
    # Step 6: Right hand lifts cube2
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="target", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True, object_name="cube", object_id=2)
    # Step 7: Right hand puts cube2 in the middle above cube0 and cube1 and releases it
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=0,
                                                relative_p=np.array([0, -0.0225, 0.045]))
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True, object_name="cube", object_id=2)
    planner.open_hand("right")
    # Step 8: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
