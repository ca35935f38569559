# attempts: 5,000 nested brackets
# effect: parser
x = @@REPEAT:5000:[@@@@REPEAT:5000:]@@
