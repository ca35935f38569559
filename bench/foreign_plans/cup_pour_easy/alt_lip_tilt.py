# note: after seed 0, the lip target was raised from 9 to 14 cm above the bowl's storage point: my numbers put the
# tilted mug into the bowl's rim (a geometry slip of mine, not a planner matter).
# Use the cup's functional pour@lip point: bring the lip over the bowl's storage point and tip the cup in
# stages (loop over tilt angles), keeping the lip over the bowl at each stage.
def step(planner):
    import numpy as np
    env = planner.env

    # Step 1: grasp the cup
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("cup", 0, "grasp", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", "cup", 0)

    # Step 2: lift it straight up 12 cm
    c = [Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                    hand_key_point=get_point_in_env(env, type_name="cup", obj_id=0),
                    object_key_point=get_point_in_env(env, type_name="cup", obj_id=0) + np.array([0, 0, 0.12])),
         Constraint(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                    hand_axis=get_axis_in_env(env, "z", obj_type="cup", obj_id=0), object_axis=np.array([0, 0, 1.0]))]
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)

    # Step 3: tip it over the bowl, toward +y (the bowl is to the cup's left)
    bowl = get_point_in_env(env, "storage", "bowl", 0)
    for deg in (40, 80, 120):
        a = np.radians(deg)
        up = np.array([0.0, np.sin(a), np.cos(a)])
        c = [Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                        hand_key_point=get_point_in_env(env, "lip", "cup", 0),
                        object_key_point=bowl + np.array([0.0, -0.02, 0.14])),
             Constraint(env=env, type="parallel", end_effector_frame="r_hand_base_link",
                        hand_axis=get_axis_in_env(env, "z", obj_type="cup", obj_id=0), object_axis=up)]
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cup", object_id=0)
