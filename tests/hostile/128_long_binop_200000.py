# attempts: 1 + 1 + ... 200,000 terms (left-recursive BinOp, deep AST)
# effect: parser
x = 1@@REPEAT:200000: + 1@@
