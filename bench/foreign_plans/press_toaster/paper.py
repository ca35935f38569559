# press_toaster in the paper prompt's style, written from the task YAML and the toaster's annotations (its "press"
# operation on lever_top), not from the reference plan: press posture, fingertip onto the lever, the lever to
# openness 1 with the hand riding on it, back.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand gets ready to press (index finger extended)
    planner.hand_press("right")
    # Step 2: Right index fingertip moves onto the toaster's lever
    constraint_r = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right")
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(target_effector_pose, "right", attach_obj=False)
    # Step 3: Right hand pushes the lever all the way down (openness 1)
    constraint_down = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="right", openness=1.0)
    _, target_down_pose = planner.generate_end_effector_pose(constraint_down, "right")
    planner.move_to_pose_with_screw(target_down_pose, "right", attach_obj=True, object_name="toaster", object_id=0)
    # Step 4: Right hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
