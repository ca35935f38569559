# task: close_drawer
# cheat: makes the worker's physics blow up (qvel 1e30 on the robot) so MuJoCo's auto-reset puts every joint at model.qpos0, where the drawer is shut
# step: blow it up
env = planner.env
m, d = env.model, env.data
d.qvel[:] = 1e30
env.step(env.joint_positions())
# step: let it settle
for i in range(30):
    env.step(env.joint_positions())
