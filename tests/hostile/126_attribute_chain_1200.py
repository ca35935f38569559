# attempts: a 1,200-deep attribute chain: small, parses, but deep enough for recursive AST visitors
# effect: parser
x = np.eye(2)@@REPEAT:1200:.T@@
