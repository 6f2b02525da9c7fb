"""``python -m urkin`` is the ``urkin`` command."""

import sys

from urkin.cli import main

sys.exit(main())
