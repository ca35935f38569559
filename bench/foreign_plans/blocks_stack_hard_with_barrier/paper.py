# blocks_stack_hard_with_barrier in the paper prompt's style, written from the task YAML (cube 0 on the table,
# cubes 1 and 2 on a 3 cm platform, walls behind; cube 0 has a "target": the stacking spot) and the planner API:
# both hands pinch at once, lift high over the barriers, cube 0 to its target, cube 1 and cube 2 onto it.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand pinches cube0 and right hand pinches cube1 (on the platform) at the same time
    planner.hand_pre_pinch("all")
    constraint_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
    _, pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[False, False])
    planner.hand_pinch("left", pinch_object="cube", obj_id=0)
    planner.hand_pinch("right", pinch_object="cube", obj_id=1)
    # Step 2: Both hands lift their cubes 12 cm, well over the platform and the low block
    constraint_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                                relative_obj_name="cube", relative_obj_id=0,
                                                relative_p=np.array([0, 0, 0.12]))
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=1,
                                                relative_p=np.array([0, 0, 0.12]))
    _, pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[True, True],
                                    object_name=["cube", "cube"], object_id=[0, 1])
    # Step 3: Left hand puts cube0 at its target (the stacking spot on the table), lets go and goes back
    constraint_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="left")
    _, pose_l = planner.generate_end_effector_pose(constraint_l, hand_name="left")
    planner.move_to_pose_with_screw(pose_l, "left", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left", attach_obj=False)
    # Step 4: Right hand puts cube1 on cube0
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=0,
                                                relative_p=np.array([0, 0, 0.045]))
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(pose_r, "right", attach_obj=True, object_name="cube", object_id=1)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
    # Step 5: Right hand pinches cube2 on the platform and lifts it
    planner.hand_pre_pinch("right")
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="pinch", hand_name="right")
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(pose_r, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=2)
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=2,
                                                relative_p=np.array([0, 0, 0.12]))
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(pose_r, "right", attach_obj=True, object_name="cube", object_id=2)
    # Step 6: Right hand puts cube2 on cube1 and returns to its initial pose
    constraint_r = planner.generate_constraints(obj_name="cube", obj_id=2, action="move", hand_name="right",
                                                relative_obj_name="cube", relative_obj_id=1,
                                                relative_p=np.array([0, 0, 0.045]))
    _, pose_r = planner.generate_end_effector_pose(constraint_r, hand_name="right")
    planner.move_to_pose_with_screw(pose_r, "right", attach_obj=True, object_name="cube", object_id=2)
    planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right", attach_obj=False)
