"""How the CLI tests run the command as a user would: `python -m lgekf` (same as the `lgekf` script)."""

import sys


def cli_command():
    return (sys.executable, "-m", "lgekf")


def track_error_line(tmp_path, capsys, text, args):
    """Run ``lgekf track IN -o OUT *args`` in process (``lgekf.cli.main``, what the command runs) on a file holding
    ``text``: assert exit status 2, one line on stderr and no output file; return that line."""
    from lgekf.cli import main

    src = tmp_path / "in.csv"
    src.write_text(text)
    out = tmp_path / "out.csv"
    status = main(["track", str(src), "-o", str(out), *args])
    err = capsys.readouterr().err
    assert status == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert not out.exists()
    return lines[0]
