# task: block_stack_single
# cheat: idles (commanded, simulated holds) past twice the task's 20 s time limit, then does the reference plan: an episode longer than any budget must not be judged or kept
# step: idle for 45 s
hold = planner.env.joint_positions()
for k in range(45 * 50):
    planner.env.step(hold)
    planner.on_step(hold)
# step: pinch cube 1 with the right hand
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)
# step: lift and place
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")
