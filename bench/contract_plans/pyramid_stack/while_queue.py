# rule probe (item 1): while. The prompt forbids `while`; an LLM working through a queue of jobs writes
# `while jobs:`. The jobs: left hand puts cube 0 on its target (the pyramid's left base); right hand puts cube 1
# 4.2 cm to the right of cube 0 (-y); right hand puts cube 2 across both, 4.5 cm up and 2.1 cm right of cube 0.
# style: our `# step:` blocks; a list of dicts consumed by a while loop.
# step: build the pyramid, one cube at a time
jobs = [
    {"cube": 0, "hand": "left", "on": None, "offset": None},
    {"cube": 1, "hand": "right", "on": 0, "offset": [0.0, -0.042, 0.004]},
    {"cube": 2, "hand": "right", "on": 0, "offset": [0.0, -0.021, 0.046]},
]
while jobs:
    job = jobs.pop(0)
    hand, cid = job["hand"], job["cube"]
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints(obj_name="cube", obj_id=cid, action="pinch", hand_name=hand)
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=False)
    planner.hand_pinch(hand, pinch_object="cube", obj_id=cid)
    c = planner.generate_constraints(obj_name="cube", obj_id=cid, action="move", hand_name=hand,
                                     relative_obj_name="cube", relative_obj_id=cid, relative_p=np.array([0, 0, 0.08]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=cid)
    if job["on"] is None:
        c = planner.generate_constraints(obj_name="cube", obj_id=cid, action="target", hand_name=hand)
    else:
        c = planner.generate_constraints(obj_name="cube", obj_id=cid, action="move", hand_name=hand,
                                         relative_obj_name="cube", relative_obj_id=job["on"],
                                         relative_p=np.array(job["offset"]))
    _, p = planner.generate_end_effector_pose(c, hand_name=hand)
    planner.move_to_pose_with_screw(p, hand, attach_obj=True, object_name="cube", object_id=cid)
    planner.open_hand(hand)
    if hand == "left":
        planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
