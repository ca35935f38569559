# verb: press (item 3) on a new task spec (tasks/press_toaster_left.yaml: the red toaster on the left, the left
# index presses): action="press" at the lever, then with openness=1.0, by the left hand.
# style: the paper's `def step(planner):`, one step.
def step(planner):
    planner.hand_press("left")
    c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    c = planner.generate_constraints(obj_name="toaster", obj_id=0, action="press", hand_name="left", openness=1.0)
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, hand_name="left")
