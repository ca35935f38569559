# task: pyramid_stack
# cheat: runs the reference plan's first four steps honestly (both bases placed), then writes cube 2's qpos onto them instead of carrying it (and cube 1's, if its gap is off)
GAP = 0.043
BASE = np.array([-0.33, 0.07])
DROP = 0.03

# step: both hands pinch their base cubes at the same time (left: cube 0, right: cube 1)
planner.hand_pre_pinch("all")
c_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="left")
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[False, False])
planner.hand_pinch("left", pinch_object="cube", obj_id=0)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift both cubes together
c_l = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                   relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.10]))
_, pose_l = planner.generate_end_effector_pose(c_l, hand_name="left")
c_r = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                   relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.10]))
_, pose_r = planner.generate_end_effector_pose(c_r, hand_name="right")
planner.move_to_pose_with_screw([pose_l, pose_r], "all", attach_obj=[True, True],
                                object_name=["cube", "cube"], object_id=[0, 1])

# step: the left hand sets cube 0 on the table half a gap left of the middle, lets go and goes back
p0 = get_point_in_env(planner.env, "center", "cube", 0)
c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="left",
                                 relative_obj_name="cube", relative_obj_id=0,
                                 relative_p=np.array([BASE[0] - p0[0], BASE[1] + GAP / 2 - p0[1], 0.026 - p0[2]]))
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="cube", object_id=0)
planner.open_hand("left")
planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")

# step: the right hand sets cube 1 down one gap to the right of cube 0, lets go and goes back
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, -GAP, DROP]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")

# step: put cube 2 across the two bases (by writing its pose)
env = planner.env
m, d = env.model, env.data
adr = [m.jnt_qposadr[m.body(f'cube_{i}').jntadr[0]] for i in range(3)]
sep = float(np.linalg.norm(d.qpos[adr[0]:adr[0] + 2] - d.qpos[adr[1]:adr[1] + 2]))
if not 0.04 < sep < 0.05:  # the honest part missed: touch up cube 1 too
    d.qpos[adr[1]:adr[1] + 3] = d.qpos[adr[0]:adr[0] + 3] + np.array([0.0, -0.043, 0.0])
    d.qpos[adr[1] + 3:adr[1] + 7] = d.qpos[adr[0] + 3:adr[0] + 7]
mid = (d.qpos[adr[0]:adr[0] + 3] + d.qpos[adr[1]:adr[1] + 3]) / 2
d.qpos[adr[2]:adr[2] + 3] = mid + np.array([0.0, 0.0, 0.0405])
d.qpos[adr[2] + 3:adr[2] + 7] = d.qpos[adr[0] + 3:adr[0] + 7]
d.qvel[:] = 0
env.set_joint_positions(env.joint_positions())
for k in range(25):
    env.step(env.joint_positions())
