# attempts: bytes that are not UTF-8 in the plan file
# effect: parser
# step: bad bytes
x = '@@INVALID_UTF8@@'
