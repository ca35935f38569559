# Reference plan for open_safe_door: the right hand grasps the door's vertical handle bar, swings the door open
# about its vertical hinge (openness 1: 90 deg; the grip rolls about the bar on the way), then lets go.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: the right hand grasps the handle bar
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="safe", obj_id=0)
    # Step 2: pull the door open
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="grasp", hand_name="right", openness=1)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
    # Step 3: let go
    planner.open_hand("right")
