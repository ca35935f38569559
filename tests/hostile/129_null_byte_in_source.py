# attempts: a NUL byte inside the plan text
# effect: parser
# step: nul
x = 1@@NUL@@
