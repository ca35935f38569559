# attempts: mujoco.mj_saveModel(model, path) (binary .mjb), mujoco from HumanoidEnv.__init__.__globals__
# effect: file
# needs: planner
mj = np.ma.core.operator.attrgetter('__class__.__init__.__globals__')(planner.env)['mujoco']
mj.mj_saveModel(planner.env.model, '@@MARKER_DIR@@/model.mjb', None)
