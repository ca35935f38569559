# The flip, but robust the way a cautious user writes it: try target1/target2; if that fails, come back home
# and try again with the fingers in the press posture; last resort, pinch and lift.
def step(planner):
    def flip():
        for action in ("target1", "target2"):
            cons = planner.generate_constraints("laptop", 0, action, "right")
            _, pose = planner.generate_end_effector_pose(cons, "right")
            planner.move_to_pose_with_screw(pose, "right", attach_obj=False)

    done = False
    for posture in ("open", "press"):
        if done:
            break
        try:
            if posture == "press":
                planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
                planner.hand_press("right")
            flip()
            done = True
        except Exception as exc:
            print(posture, "flip failed:", exc)
    if not done:
        planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
        planner.hand_pre_pinch("right")
        cons = planner.generate_constraints("laptop", 0, "pinch", "right")
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
        planner.hand_pinch("right", "laptop", 0)
        cons = planner.generate_constraints("laptop", 0, "pinch", "right", openness=0.85)
        _, pose = planner.generate_end_effector_pose(cons, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="laptop", object_id=0)
        planner.open_hand("right")
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
