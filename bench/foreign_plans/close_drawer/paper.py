from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand moves to grasp the drawer handle
    planner.hand_pre_grasp("left")
    constraint_l = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_l, "left")
    planner.move_to_pose_with_screw(target_effector_pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: Left hand pushes the drawer back to an openness of 0
    constraint_close = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0)
    _, target_close_pose = planner.generate_end_effector_pose(constraint_close, "left")
    planner.move_to_pose_with_screw(target_close_pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 3: Left hand releases the drawer handle
    planner.open_hand("left")
