# attempts: repeated 1500x1500 matmuls (CPU in BLAS) for ever
# effect: hang
a = np.ones((1500, 1500)) / 1500
for i in range(10**9):
    a = a @ a
