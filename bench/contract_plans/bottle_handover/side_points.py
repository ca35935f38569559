# verb: grasp-to-grasp hand-over of a round body (item 3), on a new task spec (tasks/bottle_handover.yaml),
# naming the grips: the right hand takes the bottle at "side" (from the robot's side), the left hand at
# "side_left" (its own side of the bottle), as the family's annotations list them; helper functions, defined
# again in each step since variables do not carry over reliably.
# style: helper functions per step, keyword arguments throughout.
# step: right hand grasps the bottle at its side and lifts it to the hand-over pose
def grasp_with(hand, point):
    planner.hand_pre_grasp(hand)
    cons = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name=hand, point=point)
    _, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
    planner.hand_grasp(hand, grasp_object="bottle", obj_id=0)

def carry(hand, action):
    cons = planner.generate_constraints(obj_name="bottle", obj_id=0, action=action, hand_name=hand)
    _, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="bottle", object_id=0)

grasp_with("right", "side")
carry("right", "target")

# step: left hand takes the bottle at its left side, the right hand lets go
def grasp_with(hand, point):
    planner.hand_pre_grasp(hand)
    cons = planner.generate_constraints(obj_name="bottle", obj_id=0, action="grasp", hand_name=hand, point=point)
    _, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
    planner.hand_grasp(hand, grasp_object="bottle", obj_id=0)

grasp_with("left", "side_left")
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: left hand stands the bottle on the left and lets go
def carry(hand, action):
    cons = planner.generate_constraints(obj_name="bottle", obj_id=0, action=action, hand_name=hand)
    _, pose = planner.generate_end_effector_pose(cons, hand_name=hand)
    planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="bottle", object_id=0)

carry("left", "target")
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
