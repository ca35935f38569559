# attempts: print in a loop: 10**7 lines of 100 bytes
# effect: output
# step: chatter
for i in range(10**7):
    print(i, 'B' * 100)
