# press_toaster, written with explicit constraints: the right index fingertip on the lever's top, pointing down,
# then the same spot 4 and 8 cm lower (the lever's travel), then the hand back.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    planner.hand_press("right")
    planner.ignore_collision("toaster", 0)  # the fingertip is meant to touch the lever
    top = get_point_in_env(planner.env, "lever_top", "toaster", 0)
    for depth in (-0.02, 0.0, 0.04, 0.085):
        c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                        hand_key_point=get_point_in_env(planner.env, "press_point_base_right_hand"),
                        object_key_point=top - np.array([0.0, 0.0, depth]), name="fingertip on the lever"),
             Constraint(planner.env, "angle", "r_hand_base_link",
                        hand_axis=get_axis_in_env(planner.env, "right_press_axis"),
                        object_axis=np.array([0.0, 0.0, -1.0]), lower=0.0, upper=np.radians(30),
                        name="fingertip down")]
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right")
    planner.restore_collision("toaster", 0)
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
