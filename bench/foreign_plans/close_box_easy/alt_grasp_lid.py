# Instead of pushing: grasp the lid's front tab and turn it shut (openness=0), then let go.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand grasps the box lid
    planner.hand_pre_grasp("right")
    constraint_r = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="box", obj_id=0)
    # Step 2: Right hand turns the lid down to an openness of 0
    constraint_r = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=0.0)
    _, pose = planner.generate_end_effector_pose(constraint_r, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
    # Step 3: Right hand releases the lid and goes back
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
