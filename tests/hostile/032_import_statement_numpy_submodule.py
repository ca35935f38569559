# attempts: the loosened checker's own `import`: from numpy.ma import core, then core.re.enum.bltns
# effect: file
from numpy.ma import core
import numpy.random.bit_generator as bg
B = core.re.enum.bltns
f = B.open('@@MARKER_DIR@@/import_statement', 'w')
f.write('x')
f.close()
