# Reference plan for rotate_safe_knob: the right hand pinches the knob's fin and turns it with the knob's own joint
# (a pinch point on the knob: openness is the knob's turn) to openness 0.9 (108 deg, past the 90 asked: a held knob
# lags the hand by some degrees), then lets go. Not to its stop at 1: a hand twisting against the stop left it
# sprung, and the knob turned back as the fingers let go.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: pinch the knob's fin
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="safe", obj_id=0)
    # Step 2: turn the knob to openness 0.9 (108 deg)
    c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", openness=0.9)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
    # Step 3: let go
    planner.open_hand("right")
