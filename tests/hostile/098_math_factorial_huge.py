# attempts: math.factorial(10**8): minutes of bignum arithmetic in one C call
# effect: hang
x = math.factorial(10**8)
