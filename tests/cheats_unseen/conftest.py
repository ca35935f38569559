# The cheating plans are plans, not test modules: tests/test_cheats.py and bench/cheats.py run them.
collect_ignore_glob = ["*.py"]
