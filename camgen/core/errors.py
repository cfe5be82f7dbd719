"""The project's error contract: one base class, one subclass per kind of failure.

Every subclass also derives from the matching builtin, so callers may catch either
``camgen.core.errors.SpecError`` or plain ``ValueError``. Messages are one line, in the
user's terms (field names, mm, degrees); the CLI prints them and exits with code 2.
"""
from __future__ import annotations


class CamgenError(Exception):
    """Base of every error camgen and linkgen raise on purpose."""


class SpecError(CamgenError, ValueError):
    """A template or a Python call asks for something invalid.

    ``field`` is the path of the offending field (``motion[2].angle``) when known;
    ``str(error)`` always starts with it.

    Parameters
    ----------
    message : str
        What is wrong and what is allowed, in the user's units (``must be > 0 mm (got -1)``).
    field : str or None, optional
        The path of the offending key in the template (``motion[2].angle``); the message is then
        ``"<field>: <message>"``.
    """

    def __init__(self, message: str, field: str | None = None) -> None:
        self.field = field
        self.detail = message
        super().__init__(f"{field}: {message}" if field else message)

    def under(self, prefix: str) -> "SpecError":
        """The same error with its field path placed under ``prefix``."""
        field = f"{prefix}.{self.field}" if self.field else prefix
        return SpecError(self.detail, field)


class DesignError(CamgenError, ValueError):
    """A valid spec whose part cannot be made as asked (undercut, no wall round the bore)."""


class SolverError(CamgenError, ArithmeticError):
    """A numerical method failed: a singular Jacobian, or no convergence within its limits."""


class ExportError(CamgenError, OSError):
    """An output file could not be written."""
