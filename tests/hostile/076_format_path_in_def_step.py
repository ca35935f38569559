# attempts: format path to os.environ[HGEN_TEST_SECRET] inside def step(planner), appended to planner.events
# effect: env
# needs: planner
def step(planner):
    secret = '{n.random.mtrand.warnings.sys.modules[os].environ[HGEN_TEST_SECRET]}'.format(n=np)
    planner.events.append('secret ' + secret + ' ' + secret[::-1])
    print(secret)
