# DRAFT, not yet passing (0/10): the grasp pose below is reachable on all seeds 0-9, but the pre-grasp thumb tips the cup
# over (~30 deg) on the approach before the fingers close (hand_grasp: "touching: thumb").
# Reference plan: the right hand grasps the empty cup around its body from behind and to the right (index up, palm
# turned 45 deg towards the robot's middle), carries it over the plate and sets it down upright on the plate.
# The annotated side grasp (palm along the cup's own x, at half height) is 1-2 cm out of reach for the right arm
# at this table position, so the grasp is built here: the same side grasp 2.5 cm higher, with the approach
# direction fixed in the world (the cup is round; only its handle, on its +y, matters, and it stays on the far side).
# step: the right hand grasps the cup by its side and lifts it
cup_z = get_point_in_env(planner.env, "center", "cup", 0)[2]  # the cup's centre height when it stands on the table
centre = get_point_in_env(planner.env, "center", "cup", 0)
planner.hand_pre_grasp("right")
ways = []
for deg in [45, 40, 55, 30, 60]:  # approach directions in the world, most reliable first
    d = np.array([np.cos(np.radians(deg)), np.sin(np.radians(deg)), 0.0])
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="grasp", hand_name="right", point="side")
    way = c[0].meta
    way.constraints[0].object_key_point = centre - 0.055 * d + np.array([0, 0, 0.025])
    way.constraints[1] = Constraint(planner.env, "parallel", "r_hand_base_link",
                                    hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"), object_axis=d,
                                    name="palm faces the cup")
    way.constraints[2] = Constraint(planner.env, "parallel", "r_hand_base_link",
                                    hand_axis=get_axis_in_env(planner.env, "right_ring_2_index"),
                                    object_axis=np.array([0, 0, 1.0]), name="index up")
    way.approach_axis = d
    ways.append(way)
ways[0].alternatives = ways[1:]
c = list(ways[0].constraints)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="cup", obj_id=0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

# step: carry the cup above the plate, lower it onto the plate and let go
on_plate = get_point_in_env(planner.env, "support", "plate", 0) - get_point_in_env(planner.env, "center", "plate", 0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=on_plate + np.array([0, 0, cup_z + 0.06]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
c = planner.generate_constraints(obj_name="cup", obj_id=0, action="move", hand_name="right",
                                 relative_obj_name="plate", relative_obj_id=0, relative_p=on_plate + np.array([0, 0, cup_z + 0.006]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
planner.open_hand("right")

# step: take the right hand back
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
