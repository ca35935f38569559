from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the rectangular cube
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="rectangular_cube", obj_id=0)
    # Step 2: Right hand lifts the rectangular cube
    constraint_r = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    # Step 3: Right hand moves the rectangular cube to the handover position
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="rectangular_cube", obj_id=0),
            object_key_point=np.array([-0.30, 0.0, 0.15]),
        ),
    ]
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraints, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    # Step 4: Left hand pinches the rectangular cube
    planner.hand_pre_pinch("left")
    constraint_l = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="left")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    planner.move_to_pose_with_screw(target_effector_pose_l, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="rectangular_cube", obj_id=0)
    # Step 5: Right hand releases the rectangular cube and returns to its initial pose
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
    # Step 6: Left hand moves the rectangular cube above the target cube
    constraint_l = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="move", hand_name="left",
                                                relative_obj_name="target_cube", relative_obj_id=0,
                                                relative_p=np.array([0, 0, 0.065]))
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    planner.move_to_pose_with_screw(target_effector_pose_l, "left", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    # Step 7: Left hand releases the rectangular cube
    planner.open_hand("left")
    # Step 8: Left hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
