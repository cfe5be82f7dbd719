"""The assembly check's least gaps (camgen.kinds.geneva.assembly) against the same gaps worked in full: the locking
disc's least gap at each driver angle only where it can be the least (the rest bounded), and the pin's distance to
the wheel from its nearest edge, both against every point and the whole ring."""
from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

from camgen.kinds.geneva.assembly import disc_gap, least_disc_gaps
from camgen.spec import validate_spec
from tests.conftest import ROOT

TEMPLATES = {name: tomllib.loads((ROOT / "templates" / f"{name}.toml").read_text()) for name in ("geneva4", "geneva6")}


def _dense(g, ring: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """Every point's gap at every angle, the least a row: what least_disc_gaps must agree with."""
    return disc_gap(g, g.in_driver_frame(ring, alpha)).min(axis=1)


def _geometry(name: str, **changes: float):
    raw = copy.deepcopy(TEMPLATES[name])
    raw["geneva"].update(changes)
    return validate_spec(raw).geometry


@pytest.mark.parametrize("name", ["geneva4", "geneva6"])
@pytest.mark.parametrize("tolerance", [1e-3, 1e-5])
def test_the_least_disc_gap_is_the_dense_ones_where_it_is_least(name, tolerance):
    """Over a turn (3 600 angles and the engagement's ends, 3 601 at 1e-5 mm in blocks crossing the 200-angle
    seams), and round the worst angle: the same least and the same first angle to the bit, every other angle's
    entry at least that least, and the angles whose every point is bounded out larger than it."""
    g = _geometry(name)
    e = g.law.engagement
    ring = g.wheel().flatten(tolerance)
    turn = np.unique(np.concatenate([np.linspace(-math.pi, math.pi, 3601)[1:], [-e, 0.0, e]]))
    if tolerance < 1e-4:
        turn = turn[::9]                                       # the fine ring: every ninth angle (the memory)
    worst = turn[int(np.argmin(_dense(g, ring, turn)))]
    for alpha in (turn, np.linspace(worst - 1e-3, worst + 1e-3, 33)):
        dense, pruned = _dense(g, ring, alpha), least_disc_gaps(g, ring, alpha)
        assert np.argmin(pruned) == np.argmin(dense) and pruned.min() == dense.min()
        assert (pruned >= dense.min()).all() and np.isfinite(pruned).all()
        exact = pruned == dense
        assert exact[dense == dense.min()].all()
        # an inexact entry is the least over some of the points, or the least bound: above the least either way
        assert (pruned[~exact] > dense.min()).all()


def test_the_least_disc_gap_of_an_overlapping_disc_is_the_deepest_overlap():
    """A disc too large for its cutout (lock clearance 0: it touches the wheel, and 0.3 mm larger overlaps it):
    negative gaps found as the dense ones are, to the bit."""
    g = _geometry("geneva4", lock_clearance=0.0)
    ring = g.wheel().flatten(1e-3)
    alpha = np.linspace(-math.pi, math.pi, 721)
    big = type(g)(g.slots, g.centre_distance, g.pin_diameter, g.slot_clearance, g.lock_clearance,
                  g.lock_radius + 0.3, g.crank_width, g.driver_bore, g.wheel_bore)
    for geometry in (g, big):
        dense, pruned = _dense(geometry, ring, alpha), least_disc_gaps(geometry, ring, alpha)
        assert pruned.min() == dense.min() and np.argmin(pruned) == np.argmin(dense)
    assert _dense(big, ring, alpha).min() < -0.25


def test_the_pin_gap_from_the_nearest_edge_is_shapelys_distance_to_the_ring():
    """The design's pin clearance (the nearest edge's distance, from a tree of the fine outline's edges) against
    shapely's distance from the pin's centres to the whole ring, at the assembly's own angles: to the bit."""
    import shapely

    from camgen.kinds.geneva import assembly

    g = _geometry("geneva6")
    ring = g.wheel().flatten(1e-5)
    a = np.linspace(-g.law.engagement, g.law.engagement, 301)
    turn = -(math.pi - g.law.motion(a)[0] - a)
    x, y = g.crank_radius - g.centre_distance * np.cos(-a), -g.centre_distance * np.sin(-a)
    centres = shapely.points(np.cos(turn) * x - np.sin(turn) * y, np.sin(turn) * x + np.cos(turn) * y)
    whole = shapely.distance(shapely.LinearRing(ring), centres)
    assert (assembly.edge_distances(assembly.edge_tree(ring), centres) == whole).all()
    check = assembly.check_assembly(g)
    # half the slot clearance, less at most the fine outline's chord tolerance (1e-5 mm)
    assert g.slot_clearance / 2 - 1e-5 <= check.pin_clearance_min_mm <= g.slot_clearance / 2
