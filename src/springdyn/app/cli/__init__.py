"""The ``springdyn`` command line: a thin layer over the Python API (no physics here)."""
