"""humanoidgen: bimanual dexterous manipulation tasks and demonstrations for the Unitree H1-2."""

__version__ = "0.1.0"
