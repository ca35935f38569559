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
    # Step 3: Right hand places the cup directly over the plate
    constraint_r = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                                relative_obj_name="plate", relative_obj_id=0,
                                                relative_p=np.array([0, 0, 0.06]))
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=True, object_name="cup", object_id=0)
    # Step 4: Right hand releases the cup
    planner.open_hand("right")
    # Step 5: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
