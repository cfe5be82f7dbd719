"""How far a synthesis has gone, and how a caller stops it: the record :func:`linkgen.synthesis.run.synthesize`
hands its ``progress`` callback, and the error it raises when the callback says stop. No I/O."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from camgen.core.errors import CamgenError
from linkgen.synthesis.candidates import Offered


@dataclass(frozen=True)
class Progress:
    """A synthesis under way.

    Attributes
    ----------
    fraction : float
        The share of the work done, 0 to 1 (a path search: generations run of all its starts' generations; an
        analytic method: its stages); it never decreases.
    stage : str
        What runs now, in words (``"search 2 of 4, generation 130 of 1500"``).
    best : tuple of Offered
        The best candidates found so far, best first, each as it would be written (its template and the report of
        ``linkgen analyze`` on it); empty until a search or method has finished one.
    """

    fraction: float
    stage: str
    best: tuple[Offered, ...] = ()


#: what :func:`~linkgen.synthesis.run.synthesize` calls with each :class:`Progress`: True to go on, False to stop
ProgressHook = Callable[[Progress], bool]


class Cancelled(CamgenError):
    """The ``progress`` callback asked the synthesis to stop; ``best`` holds the candidates found before it did
    (best first, possibly none)."""

    def __init__(self, best: tuple[Offered, ...] = ()) -> None:
        self.best = best
        found = f"{len(best)} candidate{'s' if len(best) != 1 else ''} found before it stopped"
        super().__init__(f"synthesis cancelled ({found})")
