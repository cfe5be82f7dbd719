"""The band's check by Monte Carlo: linkages as made with their slack drawn at random, each solved over the whole
motion by the project's own solver (no I/O).

Each sample draws every pin's offset uniformly over its hole's disc of play and every length and slot line
uniformly within its tolerance (:func:`linkgen.kinematics.sensitivity.sample`, seeded), assembles that linkage's
drawing and solves it at the band's input values (:func:`linkgen.kinematics.sensitivity.perturbed`). Its
tracers' offsets across their paths and its outputs' offsets, against the band's half-widths there, say how much of
the band it reaches (at most 1, less second-order terms), and its offsets less the band's first-order prediction for
that sample are the linearisation's second-order error. Only the poses reached from the drawing without passing
where the linkage binds are compared (:attr:`linkgen.slack.band.SlackBand.reached`): the band is unbounded where it
binds, and past there a linkage as made may lock or take another branch. Samples whose drawing does not assemble
are left out, and so are the poses a sample does not reach.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.sensitivity import perturbed, sample
from linkgen.slack.band import SlackBand

#: sample paths kept for the figure
KEEP = 20


@dataclass(frozen=True)
class MonteCarlo:
    """What the samples found.

    Attributes
    ----------
    count, seed : int
        How many samples were drawn, from which seed.
    assembled : int
        How many of them assembled (the rest are left out).
    reach : dict of str to float
        For each tracer and output, the largest offset over the samples and poses as a fraction of the band's
        half-width there (at most 1 to second order).
    compared : int
        How many sample poses were compared (a pose of a sample that assembled and reaches it, where the nominal
        linkage is reached from its drawing without binding).
    outside : int
        How many sample poses lie outside the band (any tracer or output).
    second_order : dict of str to float
        For each tracer (mm) and output (rad or mm), the largest difference between a sample's offset and the
        band's first-order prediction for that sample.
    paths : dict of str to ndarray
        Each tracer's path in the first :data:`KEEP` samples that assembled (k, n, 2) mm (NaN where a sample does
        not reach a pose), for the figure.
    """

    count: int
    seed: int
    assembled: int
    reach: dict[str, float]
    compared: int
    outside: int
    second_order: dict[str, float]
    paths: dict[str, np.ndarray]


def monte_carlo(band: SlackBand, count: int, seed: int) -> MonteCarlo:
    """``count`` samples of the linkage as made (seeded by ``seed``), each solved over the band's inputs."""
    a = band.analysis
    linkage, model = a.linkage, band.model
    s = linkage.structure
    x = band.inputs[None, :]
    nominal, r = band.solution, band.response
    keep = band.reached
    names = [t.name for t in band.tracers] + [o.name for o in band.outputs]
    reach = dict.fromkeys(names, 0.0)
    second = dict.fromkeys(names, 0.0)
    paths: dict[str, list[np.ndarray]] = {t.name: [] for t in band.tracers}
    outside, assembled, compared = 0, 0, 0
    for params in sample(model, band.bounds, np.random.default_rng(seed), count):
        made = perturbed(linkage, params, model)
        if made is None:
            continue
        assembled += 1
        sol = made.solve(x)
        ok = keep & np.asarray(sol.ok, dtype=bool)
        compared += int(np.count_nonzero(ok))
        with np.errstate(invalid="ignore"):
            predicted = {p: r.points[p] @ params for p in sol.points}
            turned = {b: r.turns[b] @ params for b in r.turns}
        for t in band.tracers:
            offset = sol.points[t.name] - t.path
            across = np.abs(np.einsum("ni,ni->n", offset, t.normal))
            outside += _tally(t.name, across, t.half_width, offset - predicted[t.name], ok, reach, second)
            if len(paths[t.name]) < KEEP:
                paths[t.name].append(np.where(ok[:, None], sol.points[t.name], np.nan))
        for o in band.outputs:
            if o.rocker:
                moved = sol.angle(o.name) + made.turns[o.name]
                offset1 = np.remainder(moved - o.value + math.pi, 2 * math.pi) - math.pi
                predicted1 = turned[o.name]
            else:
                sl = s.slider_by_name[o.name]
                u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
                offset1 = (sol.points[sl.point] - nominal.points[sl.point]) @ u
                predicted1 = predicted[sl.point] @ u
            outside += _tally(o.name, np.abs(offset1), o.half_width, (offset1 - predicted1)[:, None], ok, reach,
                              second)
    return MonteCarlo(count, seed, assembled, reach, compared, outside, second,
                      {k: np.array(v) if v else np.empty((0, len(band.inputs), 2)) for k, v in paths.items()})


def _tally(name: str, offset: np.ndarray, half_width: np.ndarray, error: np.ndarray, ok: np.ndarray,
           reach: dict[str, float], second: dict[str, float]) -> int:
    """Fold one sample's offsets (n,) of ``name`` into the largest reach and second-order error; how many of its
    poses lie outside the band."""
    ok = ok & np.isfinite(offset) & np.isfinite(half_width)
    if not ok.any():
        return 0
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(half_width[ok] > 0, offset[ok] / half_width[ok], np.where(offset[ok] > 0, np.inf, 0.0))
    reach[name] = max(reach[name], float(np.max(ratio)))
    second[name] = max(second[name], float(np.max(np.linalg.norm(error[ok], axis=-1))))
    return int(np.count_nonzero(ratio > 1.0))
