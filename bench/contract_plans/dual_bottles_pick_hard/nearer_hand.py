# task coverage and the prompt's rule "use the hand nearer to the object (left hand for y > 0)": each bottle's
# hand is chosen from its centre's y; one hand after the other (grasp, then lift 10 cm with action="move"
# relative to the bottle itself), the first bottle held while the second is taken.
# style: our `# step:` blocks; a helper defined in each step; a for loop over the bottles.
# step: grasp each bottle with the hand on its side
def hand_for(obj_id):
    return "left" if get_point_in_env(planner.env, "center", "bottle", obj_id)[1] > 0 else "right"

for b in [0, 1]:
    h = hand_for(b)
    planner.hand_pre_grasp(h)
    c = planner.generate_constraints(obj_name="bottle", obj_id=b, action="grasp", hand_name=h)
    _, p = planner.generate_end_effector_pose(c, hand_name=h)
    planner.move_to_pose_with_screw(p, h, attach_obj=False)
    planner.hand_grasp(h, grasp_object="bottle", obj_id=b)

# step: lift both bottles by 10 cm, one hand after the other
def hand_for(obj_id):
    return "left" if get_point_in_env(planner.env, "center", "bottle", obj_id)[1] > 0 else "right"

for b in [0, 1]:
    h = hand_for(b)
    c = planner.generate_constraints(obj_name="bottle", obj_id=b, action="move", hand_name=h,
                                     relative_obj_name="bottle", relative_obj_id=b, relative_p=np.array([0, 0, 0.10]))
    _, p = planner.generate_end_effector_pose(c, hand_name=h)
    planner.move_to_pose_with_screw(p, h, attach_obj=True, object_name="bottle", object_id=b)
