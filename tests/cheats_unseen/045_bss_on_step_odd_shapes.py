# task: block_stack_single
# cheat: teleports cube 1 onto cube 0 and feeds the step hook commands of the wrong form: a 27-long array, a (26,1) column, a Python list of ints, booleans, a 0-d number, a complex array, an empty array
# step: teleport
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.0401])
d.qpos[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
d.qvel[:] = 0
env.set_joint_positions(env.joint_positions())
# step: odd commands
base = env.joint_positions()
hook = planner.on_step
odd = [np.append(base, 0.0), base.reshape(26, 1), [int(x) for x in base], base > 0, np.float64(0.5),
       base.astype(np.complex128) + 1j, np.zeros(0), base.astype(np.float16), base[::-1][::-1]]
for a in odd:
    try:
        hook(a)
    except Exception:
        pass
