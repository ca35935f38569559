# Reference plan for open_safe_door: the right hand grasps the door's vertical handle bar, swings the door open
# about its vertical hinge to openness 0.85 (76 deg; the grip rolls about the bar on the way), then lets go. Not to
# 1: where the arm's reach ends near 0.85, the planner would let go and grip the bar again to go on, and a second
# grip that cannot be taken there pushes the door back.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: the right hand grasps the handle bar
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="safe", obj_id=0)
    # Step 2: pull the door open
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right", openness=0.85)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
    # Step 3: let go
    planner.open_hand("right")
