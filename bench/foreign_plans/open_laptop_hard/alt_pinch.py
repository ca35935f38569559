# Same sequence with the annotation the laptop actually has (pinch@screen_edge) instead of "grasp".
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the screen edge
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="laptop", obj_id=0)
    # Step 2: Lift the screen to an openness of 0.55
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right", openness=0.55)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
    # Step 3: Let go of the screen
    planner.open_hand("right")
    # Step 4: Get under the screen
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target1", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    # Step 5: Flip it fully up
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="target2", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    # Step 6: Home
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
