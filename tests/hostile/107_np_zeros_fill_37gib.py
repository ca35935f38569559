# attempts: np.zeros((10**5, 5 * 10**4)) then fill(1): 37 GiB actually touched
# effect: memory
# step: big array
a = np.zeros((10**5, 5 * 10**4))
a.fill(1.0)
