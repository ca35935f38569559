from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the laptop
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="laptop", obj_id=0)
    # Step 2: Right hand flips the laptop up to an openness of 0.55
    constraint_open = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp", hand_name="right", openness=0.55)
    _, target_open_pose = planner.generate_end_effector_pose(constraint_open, "right")
    planner.move_to_pose_with_screw(target_open_pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Right hand releases the initial grasp
    planner.open_hand("right")
    # Step 4: Right hand moves to be under the laptop screen
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 5: Right hand moves to flip the laptop screen fully up
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 6: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
