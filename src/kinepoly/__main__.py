"""``python -m kinepoly``."""

import sys

from kinepoly.cli import main

sys.exit(main())
