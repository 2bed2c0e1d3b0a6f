"""``python -m covmap.cli``: the command line."""

import sys

from covmap.cli import main

if __name__ == "__main__":
    sys.exit(main())
