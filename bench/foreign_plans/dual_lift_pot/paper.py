from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Set both hands to the pre-grasp pose
    planner.hand_pre_grasp("all")
    # Step 2: Move the left hand to the pot's left handle and the right hand to its right handle at the same time
    constraint_l = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="pot", obj_id=0, action="grasp", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all", attach_obj=[False, False])
    # Step 3: Close both hands on the handles
    planner.hand_grasp("left", grasp_object="pot", obj_id=0)
    planner.hand_grasp("right", grasp_object="pot", obj_id=0)
    # Step 4: Lift the pot with both hands together, keeping it level
    constraint_l = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="pot", obj_id=0, action="target", hand_name="right")
    _, target_effector_pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, target_effector_pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([target_effector_pose_l, target_effector_pose_r], "all",
                                    attach_obj=[True, True], object_name=["pot", "pot"], object_id=[0, 0])
