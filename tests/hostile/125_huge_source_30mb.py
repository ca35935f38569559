# attempts: a 30 MB plan (5 million statements) in one step
# effect: parser
# step: long
@@REPEAT:5000000:x = 1\n@@
