# attempts: [0] * (4 * 10**9) (32 GB of pointers)
# effect: memory
x = [0] * (4 * 10**9)
