from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Set both hands to the pre-grasp pose
    planner.hand_pre_grasp("all")
    # Step 2: Left hand and right hand move to grasp bottle0 and bottle1 simultaneously
    constraint_l = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="bottle", obj_id=1, action="grasp", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all", attach_obj=[False, False])
    # Step 3: Close both hands to grasp the bottles
    planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
    planner.hand_grasp("right", grasp_object="bottle", obj_id=1)
    # Step 4: Lift both bottles to the target position simultaneously
    constraint_l = planner.generate_constraints(obj_name="bottle", obj_id=0, action="target", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="bottle", obj_id=1, action="target", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all",
                                    attach_obj=[True, True], object_name=["bottle", "bottle"], object_id=[0, 1])
