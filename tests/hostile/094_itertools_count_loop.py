# attempts: for i in np.ma.extras.itertools.count(): pass
# effect: hang
for i in np.ma.extras.itertools.count():
    pass
