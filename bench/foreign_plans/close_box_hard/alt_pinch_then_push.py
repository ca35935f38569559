# Pinch the lid tab (not a grasp), bring it down to 0.3, let go, then push it the rest of the way
# with target1/target2 as in close_box_easy.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the lid tab
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="box", obj_id=0)
    # Step 2: Bring the lid down to openness 0.3
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="pinch", hand_name="right", openness=0.3)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
    # Step 3: Let go of the lid
    planner.open_hand("right")
    # Step 4: Push the lid shut from above
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="target1", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    # Step 5: Back to the initial pose
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
