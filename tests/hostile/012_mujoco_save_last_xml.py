# attempts: mujoco (get_point_in_env.__globals__['mujoco']): mj_saveLastXML after loading a tiny XML, and MjSpec.to_file
# effect: file
# step: mujoco writes files too
mj = np.ma.core.operator.attrgetter('__globals__')(get_point_in_env)['mujoco']
m = mj.MjModel.from_xml_string('<mujoco/>')
mj.mj_saveLastXML('@@MARKER_DIR@@/last.xml', m)
spec = mj.MjSpec()
spec.compile()
spec.to_file('@@MARKER_DIR@@/spec.xml')
