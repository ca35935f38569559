from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the laptop screen from above
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="laptop", obj_id=0)
    # Step 2: Right hand adjusts the laptop screen's openness to 0.3
    constraint_close = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right", openness=0.3)
    _, target_close_pose = planner.generate_end_effector_pose(constraint_close, "right")
    planner.move_to_pose_with_screw(target_close_pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Right hand releases the laptop screen and moves above it
    planner.open_hand("right")
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 4: Right hand moves to flip the laptop screen fully down
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 5: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
