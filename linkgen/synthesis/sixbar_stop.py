"""When a six-bar path search stops: the four-bar's stall and collapse (:mod:`linkgen.synthesis.stop`), the stall
asked of the population's median as well as of its best.

A six-bar search's best energy can stand still for well over the four-bar's 50 generations while the population
is still descending towards a better basin: on the twelve timed points of a known Watt I
(tests/synthesis/test_sixbar.py, seed 1, population 15 a number) the best sat at 1.54 mm^2 from generation 130 to
270 while the median fell from 5.3e3 to 4.2e3 mm^2, and then the best dropped to 0.64 mm^2, from which the polish
reaches the known linkage (5e-26 mm^2). The four-bar's rule alone stopped that search at generation 177 and
returned 1.54 mm^2. So a six-bar search stalls only once both its best and its median energy have improved by no
more than the rule's ``rtol`` (relative, plus ``atol``) over the rule's ``generations``: a population that has
stopped moving. Its collapse is the four-bar's.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from linkgen.synthesis.stop import Rule, why_stop


def why_stop_six(best: Sequence[float], median: Sequence[float], energies: np.ndarray, rule: Rule) -> str | None:
    """Why a six-bar search should stop after the generations whose best and median energies are ``best`` and
    ``median`` (one each a generation, oldest first; mm^2), its population's energies now ``energies``:
    "collapse" (:func:`linkgen.synthesis.stop.why_stop`), "stall" where both histories have stalled, or None."""
    why = why_stop(best, energies, rule)
    if why == "stall" and why_stop(median, energies, rule) != "stall":
        return None
    return why
