# attempts: catastrophic backtracking in re (np.random.bit_generator.re): one C call that never returns
# effect: hang
np.random.bit_generator.re.match('(a+)+$', 'a' * 60 + '!')
