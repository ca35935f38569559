# attempts: grow a list by 64 MiB chunks up to 40 GiB (no single big request)
# effect: memory
# step: slow growth
chunks = []
for i in range(640):
    chunks.append(np.ones(8 * 2**20))
