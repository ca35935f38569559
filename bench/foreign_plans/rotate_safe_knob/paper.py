from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the knob of the safe
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="safe", obj_id=0)
    # Step 2: Right hand rotates the knob to an openness of 1
    constraint_turn = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", openness=1)
    _, target_turn_pose = planner.generate_end_effector_pose(constraint_turn, "right")
    planner.move_to_pose_with_screw(target_turn_pose, "right", attach_obj=True, object_name="safe", object_id=0)
    # Step 3: Right hand releases the knob
    planner.open_hand("right")
