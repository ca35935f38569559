# Grasp the lid tab and turn the lid fully open (openness=1) instead of flipping it from under.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the box lid
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="box", obj_id=0)
    # Step 2: Right hand opens the lid to an openness of 1
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=1.0)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
    # Step 3: Right hand releases the lid
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
