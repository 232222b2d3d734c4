"""Registers the runtime subcommands of the CLI (each lives in its own module)."""
