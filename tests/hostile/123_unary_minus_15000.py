# attempts: 15,000 unary minus signs in one expression (parser/compiler recursion)
# effect: parser
x = @@REPEAT:15000:-@@1
