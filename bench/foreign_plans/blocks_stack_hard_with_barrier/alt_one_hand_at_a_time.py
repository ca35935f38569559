# blocks_stack_hard_with_barrier, another strategy: one hand at a time, never both arms in the narrow free strip
# together. The left hand brings cube 0 to the spot with explicit constraints (cube centre 2.4 cm over the table
# at y = 0.01, pinch axis down), coming from 10 cm above it; then the right hand stacks cube 1 and cube 2 in turn,
# each over the pile first and then down, found with explicit point2point constraints from the cubes' centres.
from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def place(planner, hand, cube, spot):
    frame = "l_hand_base_link" if hand == "left" else "r_hand_base_link"
    for lift in (0.10, 0.0):
        cons = [Constraint(env=planner.env, type="point2point", end_effector_frame=frame,
                           hand_key_point=get_point_in_env(planner.env, type_name="cube", obj_id=cube),
                           object_key_point=spot + np.array([0.0, 0.0, lift])),
                Constraint(env=planner.env, type="parallel", end_effector_frame=frame,
                           hand_axis=get_axis_in_env(planner.env, axis_name=f"{hand}_pinch_axis"),
                           object_axis=np.array([0.0, 0.0, -1.0]))]
        _, pose = planner.generate_end_effector_pose(cons, hand)
        planner.move_to_pose_with_screw(pose, hand, attach_obj=True, object_name="cube", object_id=cube)
    planner.open_hand(hand)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose if hand == "left" else planner.right_hand_init_pose,
                                    hand, attach_obj=False)
def pick(planner, hand, cube):
    planner.hand_pre_pinch(hand)
    c = planner.generate_constraints(obj_name="cube", obj_id=cube, action="pinch", hand_name=hand)
    _, pose = planner.generate_end_effector_pose(c, hand)
    planner.move_to_pose_with_screw(pose, hand, attach_obj=False)
    planner.hand_pinch(hand, pinch_object="cube", obj_id=cube)
def step(planner:HumanoidMotionPlanner):
    # Cube 0: the left hand, onto the free strip between the platform and the block
    pick(planner, "left", 0)
    x0 = get_point_in_env(planner.env, "center", "cube", 0)[0]
    place(planner, "left", 0, np.array([x0, 0.01, 0.024]))
    # Cube 1 then cube 2: the right hand, each 4.5 cm above the one below
    for cube, below in ((1, 0), (2, 1)):
        pick(planner, "right", cube)
        place(planner, "right", cube, get_point_in_env(planner.env, "center", "cube", below) + np.array([0.0, 0.0, 0.045]))
