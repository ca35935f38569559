from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand grasps the drawer handle
    planner.hand_pre_grasp("left")
    constraint_l = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_l, "left")
    planner.move_to_pose_with_screw(target_effector_pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: Left hand pulls the drawer out to an openness of 0.9
    constraint_open = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0.9)
    _, target_open_pose = planner.generate_end_effector_pose(constraint_open, "left")
    planner.move_to_pose_with_screw(target_open_pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 3: Left hand releases the drawer handle
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
    # Step 4: Right hand pinches the rectangular cube
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="rectangular_cube", obj_id=0)
    # Step 5: Right hand moves the cube to hand it over to the left hand
    constraint_r = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="right")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="r_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="rectangular_cube", obj_id=0),
            object_key_point=np.array([-0.30, 0.0, 0.15]),
        ),
    ]
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraints, "right")
    planner.move_to_pose_with_screw(target_effector_pose_r, "right", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    # Step 6: Left hand pinches the cube, taking it from the right hand
    planner.hand_pre_pinch("left")
    constraint_l = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="left")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, "left")
    planner.move_to_pose_with_screw(target_effector_pose_l, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="rectangular_cube", obj_id=0)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
    # Step 7: Left hand moves the cube above the open drawer and releases it
    constraints = [
        Constraint(
            env=planner.env,
            type="point2point",
            end_effector_frame="l_hand_base_link",
            hand_key_point=get_point_in_env(planner.env, type_name="rectangular_cube", obj_id=0),
            object_key_point=get_point_in_env(planner.env, point_name="storage", type_name="drawer", obj_id=0) + np.array([0, 0, 0.1]),
        ),
    ]
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraints, "left")
    planner.move_to_pose_with_screw(target_effector_pose_l, "left", attach_obj=True,
                                    object_name="rectangular_cube", object_id=0)
    planner.open_hand("left")
    # Step 8: Left hand grasps the drawer handle again
    planner.hand_pre_grasp("left")
    constraint_l = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_l, "left")
    planner.move_to_pose_with_screw(target_effector_pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 9: Left hand pushes the drawer back to an openness of 0
    constraint_close = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0)
    _, target_close_pose = planner.generate_end_effector_pose(constraint_close, "left")
    planner.move_to_pose_with_screw(target_close_pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 10: Left hand releases the drawer handle
    planner.open_hand("left")
