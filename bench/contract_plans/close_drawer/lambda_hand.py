# rule probe (item 1): lambda. The prompt forbids `lambda`; an LLM choosing "the hand nearer to the object"
# writes min(..., key=lambda h: ...). Then the paper's close_drawer: grasp the handle, push the drawer back to
# openness 0 holding it, release, go home.
# style: our `# step:` blocks.
# step: choose the hand nearer to the drawer handle and grasp it
env = planner.env
handle = get_point_in_env(env, "handle", "drawer", 0)
hands = {"left": get_point_in_env(env, "grasp_point_base_left_hand"),
         "right": get_point_in_env(env, "grasp_point_base_right_hand")}
hand = min(hands, key=lambda h: float(np.linalg.norm(hands[h] - handle)))
planner.hand_pre_grasp(hand)
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name=hand)
_, pose = planner.generate_end_effector_pose(c, hand_name=hand)
planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
planner.hand_grasp(hand, grasp_object="drawer", obj_id=0)

# step: push the drawer back to openness 0 and let go
hand = "left" if get_point_in_env(planner.env, "handle", "drawer", 0)[1] > 0 else "right"
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name=hand, openness=0.0)
_, pose = planner.generate_end_effector_pose(c, hand_name=hand)
planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="drawer", object_id=0)
planner.open_hand(hand)

# step: hand back to its initial pose
hand = "left" if get_point_in_env(planner.env, "handle", "drawer", 0)[1] > 0 else "right"
home = planner.left_hand_init_pose if hand == "left" else planner.right_hand_init_pose
planner.move_to_pose_with_screw(home, hand)
