# rule probe (item 1): names carried between steps. The prompt says "Variables do not carry over reliably
# between steps: recompute constraints and poses in each step"; this plan defines a helper and solves both
# hands' pinch poses in step 1 and uses them (and the helper) in later steps, as a programmer would.
# style: our `# step:` blocks; "all" with lists for the simultaneous pinch.
# step: plan both pinches and define a helper
def solve(obj_id, action, hand, **kw):
    cons = planner.generate_constraints(obj_name="cube", obj_id=obj_id, action=action, hand_name=hand, **kw)
    _, p = planner.generate_end_effector_pose(cons, hand_name=hand)
    return p

planner.hand_pre_pinch("all")
left_pinch = solve(0, "pinch", "left")
right_pinch = solve(1, "pinch", "right")

# step: both hands pinch their cubes at once
planner.move_to_pose_with_screw([left_pinch, right_pinch], "all", attach_obj=[False, False])
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: left hand sets cube 0 down on its target and lets go
planner.move_to_pose_with_screw(solve(0, "target", "left"), "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: right hand stacks cube 1 on cube 0 and lets go
above = solve(1, "move", "right", relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.045]))
planner.move_to_pose_with_screw(above, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
