from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand moves to be under the laptop screen
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 2: Right hand moves to flip the laptop screen up
    constraint_r = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 3: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
