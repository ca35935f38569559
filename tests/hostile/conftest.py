# The hostile plan scripts and their tools are not test modules: tests/test_hostile.py runs them.
collect_ignore_glob = ["*.py"]
