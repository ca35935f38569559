# attempts: open a mujoco.Renderer from plan code (EGL/GPU) and keep every rendered frame: memory outside numpy's own allocations
# effect: memory
# needs: planner
mj = np.ma.core.operator.attrgetter('__globals__')(get_point_in_env)['mujoco']
r = mj.Renderer(planner.env.model, 960, 1280)
frames = []
for i in range(10000):
    r.update_scene(planner.env.data)
    frames.append(r.render())
