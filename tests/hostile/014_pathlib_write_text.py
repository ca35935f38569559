# attempts: pathlib.Path.write_text, pathlib imported with the real __import__
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
imp('pathlib').Path('@@MARKER_DIR@@/pathlib_write').write_text('escaped via pathlib')
