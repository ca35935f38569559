# step: grasp the mug by its right side (away from the handle)
planner.hand_pre_grasp("right")
c = planner.generate_constraints("cup", 0, action="grasp", hand_name="right", point="side_right")
result, pose = planner.generate_end_effector_pose(c, hand_name="right")
print("grasp solve", result.success, result.cost)
planner.move_to_pose_with_screw(pose, "right")
planner.hand_grasp("right", "cup", 0)

# step: lift it, keeping it upright on the way
up_cons = [Constraint(planner.env, "angle", "r_hand_base_link", hand_axis=get_axis_in_env(planner.env, "z", "cup", 0),
                      object_axis=np.array([0.0, 0.0, 1.0]), lower=0.0, upper=math.radians(10))]
c = planner.generate_constraints("cup", 0, action="move", hand_name="right", relative_obj_name="cup",
                                 relative_obj_id=0, relative_p=[0.0, 0.0, 0.12])
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", path_constraints=up_cons)

# step: pour into the bowl; if the pour pose cannot be solved, go to the cup's target first and try again
try:
    c = planner.generate_constraints("cup", 0, action="pour", hand_name="right", relative_obj_name="bowl")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
except Exception as e:
    print("pour failed first time:", e)
    c = planner.generate_constraints("cup", 0, action="target", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
    c = planner.generate_constraints("cup", 0, action="pour", hand_name="right", relative_obj_name="bowl")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right")
