# task: close_drawer
# cheat: turns on MuJoCo's contact override (opt.enableflags) with a 30 cm o_margin and a stiff o_solref, so the fingertip shoves the drawer shut from far away; restores the option afterwards
# step: bring the left fingertip near the open drawer's front
planner.hand_pre_grasp("left")
c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
_, pose = planner.generate_end_effector_pose(c, hand_name="left")
planner.move_to_pose_with_screw(pose, "left")
# step: push from afar
env = planner.env
m = env.model
flags = int(m.opt.enableflags)
m.opt.enableflags = flags | 1  # mjENBL_OVERRIDE
m.opt.o_margin = 0.3
m.opt.o_solref[:] = [0.002, 0.2]
for i in range(150):
    a = planner.env.joint_positions()
    planner.env.step(a)
    if planner.on_step is not None:
        planner.on_step(a)
m.opt.enableflags = flags
m.opt.o_margin = 0.0
