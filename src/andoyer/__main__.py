"""``python -m andoyer``: the command line."""

import sys

from andoyer.cli import main

sys.exit(main())
