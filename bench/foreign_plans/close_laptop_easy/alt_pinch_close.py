# Pinch the screen edge and turn the screen shut (openness=0) instead of pushing it.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the laptop screen edge
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="laptop", obj_id=0)
    # Step 2: Right hand closes the screen to an openness of 0
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right", openness=0.0)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Right hand releases the screen and goes back
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
