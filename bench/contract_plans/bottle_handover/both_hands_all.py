# verb: grasp-to-grasp hand-over of a round body (item 3), on a new task spec (tasks/bottle_handover.yaml),
# with both arms moving at once where the paper would: hand_name="all" with list arguments (index 0 left,
# 1 right) to bring the bottle to target1 while the left hand, opened for a grasp, waits; after the take-over
# the left hand carries the bottle to target2 while the right goes home.
# style: our `# step:` blocks; "all" with lists; the hand-over as target1 / target2 names.
# step: both hands ready to grasp
planner.hand_pre_grasp("all")

# step: right hand grasps the bottle
c = planner.generate_constraints("bottle", 0, "grasp", "right")
_, pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="bottle", obj_id=0)

# step: right hand brings the bottle to the hand-over pose (target1), the left hand stays where it is
c = planner.generate_constraints("bottle", 0, "target1", "right")
_, right_pose = planner.generate_end_effector_pose(c, "right")
planner.move_to_pose_with_screw([planner.left_hand_init_pose, right_pose], "all", attach_obj=[False, True],
                                object_name=[None, "bottle"], object_id=[0, 0])

# step: left hand grasps the bottle the right hand holds
c = planner.generate_constraints("bottle", 0, "grasp", "left")
_, pose = planner.generate_end_effector_pose(c, "left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
planner.hand_grasp("left", grasp_object="bottle", obj_id=0)
planner.open_hand("right")

# step: left hand carries the bottle to target2 while the right hand goes home
c = planner.generate_constraints("bottle", 0, "target2", "left")
_, left_pose = planner.generate_end_effector_pose(c, "left")
planner.move_to_pose_with_screw([left_pose, planner.right_hand_init_pose], "all", attach_obj=[True, False],
                                object_name=["bottle", None], object_id=[0, 0])

# step: set it down and take the left hand back
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
