# YAML type names (cube 0 = block, cube 1 = target); the handover point is given relative to the target cube
# (relative_p) and the left hand takes the block with a whole-hand grasp at its top instead of a pinch.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Right hand pinches the block (cube 0)
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=0)
    # Step 2: Right hand carries it to the middle, 20 cm right of the target cube and 12 cm up
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="cube", relative_obj_id=1,
                                     relative_p=np.array([0.0, -0.20, 0.12]))
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    # Step 3: Left hand grasps the block's top
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="grasp", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="cube", obj_id=0)
    # Step 4: Right hand lets go and backs off
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
    # Step 5: Left hand sets the block upright on the target cube
    for dz in (0.12, 0.065):
        c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                         relative_obj_name="cube", relative_obj_id=1,
                                         relative_p=np.array([0.0, 0.0, dz]))
        _, pose = planner.generate_end_effector_pose(c, hand_name="left")
        planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    # Step 6: Left hand back home
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
