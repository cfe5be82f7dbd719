"""One check the tests of the cam kinds share: a bad value is one line naming the field, exit code 2, nothing
written."""
from __future__ import annotations

import json
from collections.abc import Callable

from click.testing import CliRunner


def assert_refused(template, change: dict, message: str, tmp_path, main=None, command: str = "build",
                   inline: Callable[[object], str] = json.dumps) -> None:
    """``camgen build template`` (or ``main``'s ``command``) with ``change`` ({dotted key: value}, as --set, each
    value written by ``inline``) fails with ``error: message...`` on one line, exit code 2, and leaves no output
    folder."""
    assert_refused_sets(template, [f"{key}={inline(value)}" for key, value in change.items()], message, tmp_path,
                        main, command)


def assert_refused_sets(template, sets: list[str], message: str, tmp_path, main=None, command: str = "build") -> None:
    """The same with ``sets`` written as the command line's ``--set KEY=VALUE`` strings."""
    if main is None:
        from camgen.cli import main

    args = [command, str(template), "-o", str(tmp_path / "out")]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert result.output.startswith(f"error: {message}") and result.output.count("\n") == 1, result.output
    assert not (tmp_path / "out").exists()
