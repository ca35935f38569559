# attempts: raise KeyboardInterrupt mid-plan
# effect: other
# step: one
x = 1
# step: interrupt
raise np.ma.core.re.enum.bltns.KeyboardInterrupt()
