# Push the drawer front shut (push@front via target1/target2) instead of grasping the handle.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand moves to the drawer front
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    # Step 2: Left hand pushes the drawer in
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target2", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    # Step 3: Left hand returns to its initial pose
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
