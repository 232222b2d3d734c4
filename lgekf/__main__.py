"""`python -m lgekf ...` is the same as the `lgekf` command."""

from lgekf.cli import run

# the guard matters: Dask's worker processes are started with "spawn", which imports this module again
# (as __mp_main__) in every worker; without it each worker would rerun the command
if __name__ == "__main__":
    run()
