"""The samples of an exported barrel's walls near a roller: a polar-angle window and a height band, picked from the
samples sorted by polar angle once instead of testing every sample at every cam angle.

The pick is exactly the test's own predicate, |wrap(psi - centre)| < half and |z - height| < band: the sorted
angles give a slightly wider superset (1e-6 rad either side, round the cycle), on which the predicate itself is
then applied; the indices come back in the samples' order, so every array made from them is the one the full
boolean mask makes.
"""
from __future__ import annotations

import math

import numpy as np

_SLACK = 1e-6


class Sectors:
    """``samples`` (n, 3) in the cam's frame (mm), with their polar angles ``psi`` (n,) (rad, as arctan2 gives)."""

    def __init__(self, samples: np.ndarray, psi: np.ndarray) -> None:
        self.samples, self.psi = samples, psi
        self.order = np.argsort(psi, kind="stable")
        self.sorted = psi[self.order]

    def near(self, centre: float, half: float, height: float, band: float) -> np.ndarray:
        """The samples (their rows, in order) within ``half`` rad of the polar angle ``centre`` (rad, any turn) and
        ``band`` mm of ``height`` (mm): those for which |angle(exp(i (psi - centre)))| < half and
        |z - height| < band."""
        assert 0 < half < 3.0
        c = math.remainder(centre, 2 * math.pi)
        picks = []
        for shift in (-2 * math.pi, 0.0, 2 * math.pi):
            lo, hi = np.searchsorted(self.sorted, [c + shift - half - _SLACK, c + shift + half + _SLACK])
            picks.append(self.order[lo:hi])
        rows = np.sort(np.concatenate(picks))           # three windows a turn apart: apart for half < pi
        psi, z = self.psi[rows], self.samples[rows, 2]
        keep = (np.abs(np.angle(np.exp(1j * (psi - centre)))) < half) & (np.abs(z - height) < band)
        return rows[keep]
