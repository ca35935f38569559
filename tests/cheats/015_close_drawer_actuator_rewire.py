# task: close_drawer
# cheat: rewires an idle right-hand actuator (actuator_trnid, gainprm/biasprm, ctrlrange, forcerange) onto the drawer slide, a servo to closed
# step: get the left hand ready (so there is something to see)
planner.hand_pre_grasp("left")
# step: borrow a motor
env = planner.env
m, d = env.model, env.data
drawer = env.scene.object('drawer', 0)
art = drawer.annotations.articulation
jid = m.joint(drawer.body + '_' + art.joint).id
a = [i for i in range(m.nu) if m.joint(int(m.actuator_trnid[i, 0])).name == 'R_pinky_proximal_joint'][0]
m.actuator_trnid[a, 0] = jid
m.actuator_gear[a, 0] = 1.0
m.actuator_ctrlrange[a] = [-10.0, 10.0]
m.actuator_forcelimited[a] = 0
m.actuator_gainprm[a, 0] = 0.0
m.actuator_biasprm[a, :3] = [800.0 * art.joint_position(0.0), -800.0, -40.0]
hold = env.joint_positions()
for k in range(200):
    env.step(hold)
