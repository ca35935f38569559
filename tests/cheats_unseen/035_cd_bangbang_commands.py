# task: close_drawer
# cheat: commands only the ends of every actuator's ctrlrange, flipping each control step (no write to the state), hoping the replay's physics goes unstable and MuJoCo's auto-reset (qpos0: drawer shut) fires there
# step: flail
env = planner.env
lo = env.clip(np.full(26, -1e3))
hi = env.clip(np.full(26, 1e3))
for k in range(400):
    a = np.where((np.arange(26) + k) % 2 == 0, lo, hi)
    env.step(a)
    if planner.on_step is not None:
        planner.on_step(a)
