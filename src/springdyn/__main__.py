"""``python -m springdyn``: the command line, as the ``springdyn`` script runs it."""

import sys

from springdyn.app.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
