"""One check the tests of the cam kinds share: a bad value is one line naming the field, exit code 2, nothing
written."""
from __future__ import annotations

import json

from click.testing import CliRunner


def assert_refused(template, change: dict, message: str, tmp_path) -> None:
    """``camgen build template`` with ``change`` ({dotted key: value}, as --set) fails with ``error: message...`` on
    one line, exit code 2, and leaves no output folder."""
    from camgen.cli import main

    args = ["build", str(template), "-o", str(tmp_path / "out")]
    for key, value in change.items():
        args += ["--set", f"{key}={json.dumps(value)}"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {message}") and result.output.count("\n") == 1, result.output
    assert not (tmp_path / "out").exists()
