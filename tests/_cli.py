"""How the CLI tests run the command as a user would: `python -m lgekf` (same as the `lgekf` script)."""

import sys


def cli_command():
    return (sys.executable, "-m", "lgekf")
