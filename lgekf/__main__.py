"""`python -m lgekf ...` is the same as the `lgekf` command."""

import sys

from lgekf.cli import main

sys.exit(main())
