# Reference plan for press_toaster: the index fingertip comes down onto the lever's top and pushes it to the
# bottom of its slot (the toaster's annotated "press"), then lifts off.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: extend the right index finger and set its tip on top of the lever
    planner.hand_press("right")
    c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    # Step 2: press the lever all the way down (openness 1)
    c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right", openness=1)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    # Step 3: take the hand back
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
