# attempts: logging.FileHandler on a logger writes a log file
# effect: file
B = np.random.bit_generator.re.enum.bltns
imp = B.getattr(B, '__import__')
logging = imp('logging')
h = logging.FileHandler('@@MARKER_DIR@@/escaped.log')
lg = logging.getLogger('hostile')
lg.addHandler(h)
lg.error('escaped through logging')
h.close()
