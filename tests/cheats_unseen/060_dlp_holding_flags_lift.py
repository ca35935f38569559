# task: dual_lift_pot
# cheat: sets the planner's own 'holding' state (ctx.hands[side].held / grip) for both hands, as if the pot were grasped, and lifts the pot 10 cm by qpos while the hands hover: what is held is the planner's belief, not a contact
# step: believe it is held
env = planner.env
m, d = env.model, env.data
pot = env.scene.object('pot', 0)
for side in ("left", "right"):
    hs = planner.ctx.hands[side]
    hs.held = pot
    hs.grip = "grasp"
j = m.body(pot.body).jntadr[0]
a = m.jnt_qposadr[j]
hold = env.joint_positions()
for k in range(50):
    d.qpos[a + 2] += 0.002
    d.qvel[:] = 0
    env.step(hold)
    planner.on_step(hold)
