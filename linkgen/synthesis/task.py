"""The ``[task]`` of a synthesis template, validated into a frozen spec with one-line errors naming the field.

A synthesis template states what the linkage must do; ``task.kind`` picks the model::

    name = "line6"
    [task]
    kind = "path"                          # crank-rocker, slider-crank, function, motion, path
    points = [[20, 20], [20, 25], [20, 30]]
    input_angles = [30, 45, 60]            # optional: prescribed timing (degrees from the ground line)
    crank = true
    link_range = [5, 60]

Units: mm and degrees; every angle counter-clockwise. An optional ``[parts]`` table (as for
``linkgen build``) is copied into every candidate's template.
"""
from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any, ClassVar, Literal

import numpy as np
from pydantic import Field, create_model, model_validator

from camgen.core.errors import SpecError
from camgen.core.options import choose
from camgen.core.spec import MAX_LENGTH_MM, Model, name_field, read_template, unit, validate
from linkgen.spec import PartsTable

Point = tuple[float, float]

#: the least transmission angle (degrees) every candidate keeps over the motion it makes, unless the task's
#: ``min_transmission`` says otherwise: below it a linkage binds (the usual design band is 40-140 degrees)
MIN_TRANSMISSION_DEG = 30.0
#: the most values of a construction's free choice tried (crank-rocker, slider-crank): 0.1 degree round its circle
MAX_SAMPLES = 3600
#: the most link turns a motion task sweeps per free choice: three free positions pair samples^2 dyads with as
#: many, about samples^4 / 2 pairs screened
MAX_MOTION_SAMPLES = 60
#: the most values of the Burmester curves' parameter sampled: each gives up to two dyads, and every pair of the
#: dyads in the region is screened (up to (2 x samples)^2, about 8 million pairs, some 30 s on one core)
MAX_BURMESTER_SAMPLES = 1440
#: a path search's budget: at most this many independent searches, generations a search, population per unknown
MAX_STARTS, MAX_GENERATIONS, MAX_POPULATION = 64, 10_000, 100
#: ... at most this many design-target evaluations in all, the differential evolution's (starts x generations x
#: population x unknowns x points) and the polish's (below; about two minutes on one core in all) ...
MAX_PATH_EVALUATIONS = 15 * 10**7
#: ... the polish of a search counted as this many evaluations per design number squared per point (3 designs
#: polished, least squares and SLSQP over all the numbers with central differences: measured on curve18 and on 50
#: untimed points, 80 to 300 each) ...
POLISH_EVALUATIONS = 600
#: ... and at most this many generations in all (starts x generations; each costs a vectorised call or two)
MAX_PATH_GENERATIONS = 100_000
#: the Fourier method (``method = "fourier"``): at least this many targets (two harmonics of the polygon), at most
#: this many (its cost grows with them only through vectorised evaluations), and at most this many guesses polished
MIN_FOURIER_POINTS, MAX_FOURIER_POINTS, MAX_GUESSES = 5, 2000, 64
#: a six-bar path search (``linkage = "watt1"`` or ``"stephenson3"``): at most this many general-solver solves in
#: all, starts x generations x population x 10 unknowns (about 1 ms each on one core: some 3 minutes), and at most
#: this many targets
MAX_SIXBAR_SOLVES, MAX_SIXBAR_POINTS = 200_000, 100
#: ... and at least this many targets: a six-bar's 10 drawing numbers and the tracer and similarity's 6 take 8 timed
#: targets (2 equations each), 16 untimed ones (each target's crank angle is one more unknown)
MIN_SIXBAR_TIMED, MIN_SIXBAR_UNTIMED = 8, 16
#: the largest |x| or |y| of a function task's table or range, and of y = f(x) over the range
MAX_FUNCTION_VALUE = 1e12


def _mm(description: str, default: Any = ...) -> Any:
    return Field(default, description=description, json_schema_extra=unit("mm"))


def _deg(description: str, default: Any = ...) -> Any:
    return Field(default, description=description, json_schema_extra=unit("degrees"))


def _count(description: str, default: int, lo: int, hi: int) -> Any:
    return Field(default, ge=lo, le=hi, description=description)


def _check_range(name: str, pair: tuple[float, float] | None, positive: bool = True) -> None:
    """Refuse a [from, to] pair that is not increasing (or, for lengths, not positive)."""
    if pair is None:
        return
    lo, hi = pair
    if positive and lo <= 0:
        raise ValueError(f"{name}: the shortest length must be > 0 mm (got {lo:g})")
    if not lo < hi:
        raise ValueError(f"{name}: give [shortest, longest] with shortest < longest (got [{lo:g}, {hi:g}])")
    if hi > MAX_LENGTH_MM:
        raise ValueError(f"{name}: lengths must be <= {MAX_LENGTH_MM:g} mm (got {hi:g})")


def _distinct(name: str, values: Iterable[Any], what: str, gap: Callable[[Any, Any], float] | None = None) -> None:
    """Refuse two equal items (``gap(a, b)`` below 1e-9; by default |a - b|), naming both."""
    values = list(values)
    for i, a in enumerate(values):
        for j in range(i + 1, len(values)):
            if (abs(a - values[j]) if gap is None else gap(a, values[j])) < 1e-9:
                raise ValueError(f"{name}: items {i} and {j} give the same {what}; each must differ")


def _placed(name: str, points: Iterable[Iterable[float]] | None) -> None:
    """Refuse a point of the task's frame (mm) that a linkage template could not hold: each coordinate within
    MAX_LENGTH_MM of the origin, as every joint of a template."""
    for k, point in enumerate(points or ()):
        if not all(abs(v) <= MAX_LENGTH_MM for v in point):
            shown = ", ".join(f"{v:g}" for v in point)
            raise ValueError(f"{name}: item {k}, [{shown}], must lie within {MAX_LENGTH_MM:g} mm of the origin in x "
                             "and y (where a template's joints lie)")


def _transmission() -> Any:
    return Field(MIN_TRANSMISSION_DEG, ge=0, lt=90, description="least transmission angle every candidate keeps "
                 "over the motion it makes (the whole turn for a crank; 0 for no limit)",
                 json_schema_extra=unit("degrees"))


def _turn(a: float, b: float) -> float:
    """The smallest turn between two angles (degrees)."""
    return abs(math.remainder(a - b, 360.0))


def _poses(positions: Iterable[tuple[float, float, float]]) -> None:
    """Refuse a coupler pose [x mm, y mm, angle degrees] a template could not hold, or two the same."""
    positions = list(positions)
    _placed("positions", (p[:2] for p in positions))
    _distinct("positions", positions, "pose", lambda p, q: max(abs(p[0] - q[0]), abs(p[1] - q[1]),
                                                               _turn(p[2], q[2])))


class SearchOptions(Model):
    """What every optimising task shares: how many candidates to offer and the limits of the lengths."""

    link_range: tuple[float, float] | None = _mm("every link length and the ground length: [shortest, longest]",
                                                 None)
    candidates: int = _count("how many candidates to offer, best first", 5, 1, 50)
    min_transmission: float = _transmission()

    @model_validator(mode="after")
    def _ranges(self) -> SearchOptions:
        _check_range("link_range", self.link_range)
        return self


class CrankRockerTask(SearchOptions):
    """A Grashof crank-rocker whose rocker swings ``swing`` degrees with time ratio ``time_ratio``."""

    kind: Literal["crank-rocker"]
    swing: float = Field(ge=0.01, lt=180, description="rocker swing", json_schema_extra=unit("degrees"))
    time_ratio: float = Field(1.0, ge=1, le=10, description="slower stroke's time over the faster's")
    rocker: float = _mm("rocker length (pivot to pin)")
    ground: float | None = _mm("ground length, when fixed (else the free choice is swept)", None)
    samples: int = _count(f"positions of the free choice (the crank pivot on its circle) tried, at most {MAX_SAMPLES}",
                          361, 3, MAX_SAMPLES)

    @model_validator(mode="after")
    def _lengths(self) -> CrankRockerTask:
        for key in ("rocker", "ground"):
            value = getattr(self, key)
            if value is not None and not 0 < value <= MAX_LENGTH_MM:
                raise ValueError(f"{key}: must be > 0 and <= {MAX_LENGTH_MM:g} mm (got {value:g})")
        return self


class SliderCrankTask(SearchOptions):
    """A slider-crank (offset when the time ratio asks) whose slider travels ``stroke`` mm."""

    kind: Literal["slider-crank"]
    stroke: float = Field(gt=0, le=MAX_LENGTH_MM, description="slider stroke", json_schema_extra=unit("mm"))
    time_ratio: float = Field(1.0, ge=1, le=10, description="slower stroke's time over the faster's")
    offset: float | None = _mm("slider line above the crank pivot, when fixed", None)
    samples: int = _count(f"values of the free choice tried, at most {MAX_SAMPLES}", 361, 3, MAX_SAMPLES)

    @model_validator(mode="after")
    def _offset(self) -> SliderCrankTask:
        if self.offset is not None and not abs(self.offset) <= MAX_LENGTH_MM:
            raise ValueError(f"offset: must be at most {MAX_LENGTH_MM:g} mm in size (got {self.offset:g})")
        if self.offset is not None and self.time_ratio == 1 and self.offset != 0:
            raise ValueError(f"offset: a time ratio of 1 needs a centred slider, offset 0 (got {self.offset:g} mm)")
        if self.offset is not None and self.time_ratio > 1 and self.offset == 0:
            raise ValueError(f"offset: a centred slider-crank has time ratio 1; a time ratio of {self.time_ratio:g} "
                             "needs an offset (or leave offset out to sweep it)")
        return self


class FunctionTask(Model):
    """A four-bar whose rocker angle follows y = f(x) while its crank angle follows x (Freudenstein)."""

    kind: Literal["function"]
    function: str | None = Field(None, description="y as a formula of x, e.g. 'log10(x)'", max_length=200)
    table: tuple[Point, ...] | None = Field(None, description="y against x as [[x, y], ...], x increasing")
    x_range: tuple[float, float] | None = Field(None, description="x from, to (a table's ends by default)")
    input_angles: tuple[float, float] = _deg("crank angles (from the ground line) at x from and x to")
    output_angles: tuple[float, float] = _deg("rocker angles (from the ground line) at y(from) and y(to)")
    precision_points: int = _count("points at Chebyshev spacing: 3 are met exactly, more by least squares", 3, 3,
                                   1000)
    ground: float = Field(100.0, gt=0, le=MAX_LENGTH_MM, description="ground length (the scale)",
                          json_schema_extra=unit("mm"))
    min_transmission: float = _transmission()

    @model_validator(mode="after")
    def _function(self) -> FunctionTask:
        if (self.function is None) == (self.table is None):
            raise ValueError("function: give a formula (function = 'log10(x)') or a table, one of them")
        if self.table is not None:
            if len(self.table) < 3:
                raise ValueError(f"table: needs at least 3 points [x, y] (got {len(self.table)})")
            xs = [x for x, _ in self.table]
            if any(b <= a for a, b in itertools.pairwise(xs)):
                raise ValueError("table: x must increase from row to row")
        elif self.x_range is None:
            raise ValueError("x_range: missing: give x from, to for the formula")
        for key in ("table", "x_range"):
            values = getattr(self, key)
            flat = [v for row in values for v in (row if isinstance(row, tuple) else (row,))] if values else []
            if any(abs(v) > MAX_FUNCTION_VALUE for v in flat):
                raise ValueError(f"{key}: every x and y must lie within +-{MAX_FUNCTION_VALUE:g}")
        if self.x_range is not None and not self.x_range[0] < self.x_range[1]:
            raise ValueError(f"x_range: give [from, to] with from < to (got {list(self.x_range)})")
        for key in ("input_angles", "output_angles"):
            a, b = getattr(self, key)
            if a == b:
                raise ValueError(f"{key}: the two angles are the same ({a:g}); the link must turn between them")
            if abs(b - a) >= 360:
                raise ValueError(f"{key}: the link turns {abs(b - a):g} degrees, more than a full turn")
        return self


class PosesTask(SearchOptions):
    """What the tasks of a coupler line's positions share: the positions' count, checked with the poses, and a
    crank."""

    #: how many positions the task takes, and which kind takes others
    counts: ClassVar[tuple[int, int, str]]
    positions: tuple[tuple[float, float, float], ...]
    crank: bool = Field(True, description="the input must turn fully (a Grashof crank)")

    def _counted(self) -> None:
        n = len(self.positions)
        low, high, other = self.counts
        if not low <= n <= high:
            raise ValueError(f"positions: needs {low} or {high} positions [x, y, angle] (got {n}; {other})")
        _poses(self.positions)


def _positions(description: str) -> Any:
    return Field(description=f"the coupler's poses as [x mm, y mm, angle degrees]: {description}", max_length=100)


class MotionTask(PosesTask):
    """Two or three positions of a coupler line (a point and the line's direction)."""

    counts = (2, 3, "4 or 5: kind = 'burmester'")
    kind: Literal["motion"]
    positions: tuple[tuple[float, float, float], ...] = _positions("2 or 3 (4 or 5: kind 'burmester')")
    moving_pivots: tuple[Point, Point] | None = _mm("the two pivots on the coupler, drawn at the first position",
                                                    None)
    fixed_pivots: tuple[Point, Point] | None = _mm("the two ground pivots", None)
    samples: int = _count(f"values of each free choice tried, at most {MAX_MOTION_SAMPLES}", 24, 4,
                          MAX_MOTION_SAMPLES)

    @model_validator(mode="after")
    def _positions(self) -> MotionTask:
        n = len(self.positions)
        self._counted()
        _placed("moving_pivots", self.moving_pivots)
        _placed("fixed_pivots", self.fixed_pivots)
        if self.moving_pivots is not None and self.fixed_pivots is not None:
            raise ValueError("fixed_pivots: give the moving pivots or the fixed pivots, not both")
        if n == 2 and self.moving_pivots is None and self.fixed_pivots is None:
            raise ValueError("moving_pivots: two positions leave the pivots free: give moving_pivots (the fixed "
                             "pivots are then swept along their bisectors) or fixed_pivots")
        same = [k for k in ("moving_pivots", "fixed_pivots")
                if getattr(self, k) is not None and math.dist(*getattr(self, k)) < 1e-9]
        if same:
            raise ValueError(f"{same[0]}: the two pivots are at the same place")
        return self


def _box(name: str, box: tuple[Point, Point] | None) -> None:
    """Refuse a box [[x_min, y_min], [x_max, y_max]] (mm) that is empty or lies beyond what a template holds."""
    _placed(name, box)
    if box is not None:
        (x0, y0), (x1, y1) = box
        if not (x0 < x1 and y0 < y1):
            raise ValueError(f"{name}: give [[x_min, y_min], [x_max, y_max]] with min < max")


class BurmesterTask(PosesTask):
    """Four or five positions of a coupler line (Burmester theory); the dyads picked from a region of the curves."""

    counts = (4, 5, "2 or 3: kind = 'motion'")
    kind: Literal["burmester"]
    positions: tuple[tuple[float, float, float], ...] = _positions(
        "4 (the centre-point and circle-point curves) or 5 (their Ball-Burmester points)")
    centre_region: tuple[Point, Point] | None = _mm("only dyads whose ground pivot (centre point) lies inside "
                                                    "[[x_min, y_min], [x_max, y_max]]", None)
    circle_region: tuple[Point, Point] | None = _mm("only dyads whose moving pivot at the first position (circle "
                                                    "point) lies inside [[x_min, y_min], [x_max, y_max]]", None)
    curve_range: tuple[float, float] | None = _deg(
        "only dyads whose curve parameter (the dyad link's turn from position 1 to 2, counter-clockwise) lies in "
        "[from, to], 0 <= from < to <= 360", None)
    samples: int = _count(f"values of the curve parameter sampled over a turn (each gives up to two dyads, on the "
                          f"curves' two branches), at least 12, at most {MAX_BURMESTER_SAMPLES}; four positions "
                          "only", 360, 12, MAX_BURMESTER_SAMPLES)

    @model_validator(mode="after")
    def _positions(self) -> BurmesterTask:
        self._counted()
        _box("centre_region", self.centre_region)
        _box("circle_region", self.circle_region)
        if self.curve_range is not None and not 0 <= self.curve_range[0] < self.curve_range[1] <= 360:
            raise ValueError("curve_range: give [from, to] in degrees with 0 <= from < to <= 360 (got "
                             f"[{self.curve_range[0]:g}, {self.curve_range[1]:g}])")
        return self


class PathTask(SearchOptions):
    """N target points for a four-bar's coupler point, with or without the crank angles at them."""

    kind: Literal["path"]
    points: tuple[Point, ...] = _mm("the targets [x, y], in the order the coupler point meets them")
    input_angles: tuple[float, ...] | None = _deg("crank angles at the targets, from the ground line (timing)",
                                                  None)
    closed: bool = Field(False, description="the targets lie on a closed curve (the crank must turn fully)")
    crank: bool = Field(True, description="the input must turn fully (a Grashof crank)")
    coupler_range: float | None = _mm("largest |x| and |y| of the coupler point from the crank pin, in the "
                                      "coupler's frame (default: the longest link)", None)
    ground_region: tuple[Point, Point] | None = _mm("both ground pivots inside [[x_min, y_min], [x_max, y_max]]",
                                                    None)
    link_ratio: float | None = Field(None, gt=1, description="largest longest-to-shortest link ratio")
    seed: int = Field(1, ge=0, description="seed of the search: the same seed gives the same candidates")
    starts: int = _count(f"independent searches (spread over --jobs or the cluster), at most {MAX_STARTS}", 4, 1,
                         MAX_STARTS)
    generations: int = _count(f"differential evolution's generations a search, at most {MAX_GENERATIONS}, and "
                              f"starts x generations at most {MAX_PATH_GENERATIONS}", 1500, 1, MAX_GENERATIONS)
    population: int = _count(f"differential evolution's population, per unknown, at most {MAX_POPULATION}; the "
                             f"whole search at most {MAX_PATH_EVALUATIONS:.2g} design-target evaluations", 15, 5,
                             MAX_POPULATION)
    method: Literal["evolution", "fourier"] = Field(
        "evolution", description="how the path is searched: 'evolution' (differential evolution, timed or not) or "
        "'fourier' (untimed: elliptic Fourier descriptors against an atlas of coupler curves, then least squares "
        "on the true point-to-curve distances)")
    guesses: int = _count(f"the Fourier method's atlas guesses polished, best first, at most {MAX_GUESSES}", 12, 1,
                          MAX_GUESSES)
    atlas_folder: str | None = Field(None, description="where the Fourier method keeps its atlas of coupler curves "
                                     "(default: the user's cache folder, XDG_CACHE_HOME/linkgen)", max_length=4096)
    linkage: Literal["four-bar", "watt1", "watt2", "stephenson1", "stephenson2", "stephenson3"] = Field(
        "four-bar", description="the linkage searched: 'four-bar', or a six-bar, 'watt1' (Watt I), 'watt2' (Watt "
        "II), 'stephenson1' (Stephenson I), 'stephenson2' (Stephenson II, timed only) or 'stephenson3' (Stephenson "
        "III): crank = true, method 'evolution', "
        f"{MIN_SIXBAR_TIMED} to {MAX_SIXBAR_POINTS} targets with input_angles (timed), {MIN_SIXBAR_UNTIMED} to "
        f"{MAX_SIXBAR_POINTS} without (untimed: the error to the nearest point of the curve), starts x generations x "
        f"population x 10 at most {MAX_SIXBAR_SOLVES} solves; the four-bar's best on the same targets is reported "
        "next to it")

    @model_validator(mode="after")
    def _targets(self) -> PathTask:
        fourier = self.method == "fourier"
        low, high = (MIN_FOURIER_POINTS, MAX_FOURIER_POINTS) if fourier else (3, 200)
        n = len(self.points)
        if not low <= n <= high:
            raise ValueError(f"points: {'method ' + repr(self.method) if fourier else 'a path'} needs {low} to "
                             f"{high} target points (got {n})")
        _placed("points", self.points)
        _distinct("points", (x + 1j * y for x, y in self.points), "point")
        if fourier:
            self._fourier()
        if self.input_angles is not None:
            a = self.input_angles
            if len(a) != n:
                raise ValueError(f"input_angles: give one angle a point ({n} points, got {len(a)} angles)")
            _distinct("input_angles", a, "crank angle for two different points", _turn)
            steps = [b - x for x, b in itertools.pairwise(a)]
            if not (all(s > 0 for s in steps) or all(s < 0 for s in steps)):
                raise ValueError("input_angles: the crank must meet the points in order, turning one way: the angles "
                                 "must all increase or all decrease")
            if abs(a[-1] - a[0]) >= 360:
                raise ValueError(f"input_angles: they span {abs(a[-1] - a[0]):g} degrees; the points must lie "
                                 "within one turn of the crank")
        if self.closed and not self.crank:
            raise ValueError("crank: a closed path needs a crank that turns fully (crank = true)")
        if self.coupler_range is not None and not 0 < self.coupler_range <= MAX_LENGTH_MM:
            raise ValueError(f"coupler_range: must be > 0 and <= {MAX_LENGTH_MM:g} mm (got {self.coupler_range:g})")
        _box("ground_region", self.ground_region)
        if self.linkage != "four-bar":
            self._sixbar()
        elif self.method == "evolution":
            self._budget()
        return self

    def _sixbar(self) -> None:
        """Refuse what the six-bar search (:mod:`linkgen.synthesis.sixbar`) cannot take, and a budget beyond
        MAX_SIXBAR_SOLVES."""
        six = repr(self.linkage)
        if len(self.points) > MAX_SIXBAR_POINTS:
            raise ValueError(f"points: linkage {six} takes at most {MAX_SIXBAR_POINTS} targets (got "
                             f"{len(self.points)})")
        unused = [k for k in ("coupler_range", "ground_region", "link_ratio") if getattr(self, k) is not None]
        if self.method != "evolution":
            unused.insert(0, "method")
        if not self.crank:
            unused.insert(0, "crank")
        if unused:
            raise ValueError(f"{unused[0]}: linkage {six} takes link_range, min_transmission and the search's budget "
                             "with a crank that turns fully (crank = true, method 'evolution'): leave "
                             f"{unused[0]} out, or use linkage 'four-bar'")
        solves = self.starts * self.generations * self.population * 10
        if solves > MAX_SIXBAR_SOLVES:
            raise ValueError(f"generations: linkage {six} would make about {solves} solves (starts x generations x "
                             f"population x 10 unknowns), at most {MAX_SIXBAR_SOLVES}: give fewer generations, "
                             "starts or population")
        if self.linkage == "stephenson2" and self.input_angles is None:
            raise ValueError("input_angles: linkage 'stephenson2' is searched timed only: give the crank angle at "
                             "each target (input_angles), or use another linkage for an untimed path")
        least, how = ((MIN_SIXBAR_TIMED, "timed") if self.input_angles is not None else
                      (MIN_SIXBAR_UNTIMED, "untimed (no input_angles)"))
        if len(self.points) < least:
            raise ValueError(f"points: linkage {six} {how} needs at least {least} targets for its unknowns (10 "
                             f"drawing numbers, the tracer and the similarity; untimed also a crank angle a target), "
                             f"got {len(self.points)}")

    def _fourier(self) -> None:
        """Refuse what the Fourier method cannot take (beyond the targets' count, checked first): timing, a curve
        crossing itself (its atlas holds coupler curves that do not)."""
        n = len(self.points)
        if self.input_angles is not None:
            raise ValueError("input_angles: method 'fourier' is untimed: leave input_angles out, or use method "
                             "'evolution' for prescribed timing")
        crossing = _self_crossing(self.points, self.closed)
        if crossing is not None:
            i, j = crossing
            shape = "closed curve" if self.closed else "curve"
            raise ValueError(f"points: the targets' {shape} crosses itself (the side from item {i} to {i + 1} "
                             f"crosses the side from item {j} to {(j + 1) % n}): method 'fourier' matches curves "
                             "that do not cross themselves; use method 'evolution' for this one")

    def _budget(self) -> None:
        """Refuse a search too big to finish in a couple of minutes on one core (see MAX_PATH_EVALUATIONS); the
        unknowns are those :func:`linkgen.synthesis.path.problem_of` searches (and, untimed, a crank angle a
        point), the polish runs over the nine design numbers (and the crank angles)."""
        n = len(self.points)
        searched, polished = (6, 9) if self.input_angles is not None else (8 + n, 9 + n)
        if self.starts * self.generations > MAX_PATH_GENERATIONS:
            raise ValueError(f"generations: starts x generations is {self.starts * self.generations}, at most "
                             f"{MAX_PATH_GENERATIONS}: give fewer generations or starts")
        work = self.starts * (self.generations * self.population * searched + POLISH_EVALUATIONS * polished**2) * n
        if work > MAX_PATH_EVALUATIONS:
            raise ValueError(f"generations: the search would make about {work:.3g} design-target evaluations (starts "
                             f"x (generations x population x {searched} unknowns + {POLISH_EVALUATIONS} x {polished}^2 "
                             f"for the polish) x {n} points), at most {MAX_PATH_EVALUATIONS:.2g}: give fewer "
                             "generations, starts, population or points" + ("" if self.input_angles is not None else
                                                                           ", or their input_angles"))


def _self_crossing(points: Iterable[Point], closed: bool) -> tuple[int, int] | None:
    """The first two sides (indices of their first points) of the polygon through ``points`` (closed: back to the
    first) that are not neighbours and cross at a point inside both, or None."""
    p = np.asarray(list(points), dtype=float)
    a, b = p, np.roll(p, -1, axis=0)
    if not closed:
        a, b = a[:-1], b[:-1]
    k = len(a)
    i, j = np.triu_indices(k, 2)
    keep = ~((i == 0) & (j == k - 1)) if closed else np.ones(len(i), bool)
    i, j = i[keep], j[keep]

    def cross(o: Any, q: Any, r: Any) -> Any:
        return (q[:, 0] - o[:, 0]) * (r[:, 1] - o[:, 1]) - (q[:, 1] - o[:, 1]) * (r[:, 0] - o[:, 0])

    hit = ((cross(a[i], b[i], a[j]) * cross(a[i], b[i], b[j]) < 0)
           & (cross(a[j], b[j], a[i]) * cross(a[j], b[j], b[i]) < 0))
    first = np.flatnonzero(hit)
    return None if not len(first) else (int(i[first[0]]), int(j[first[0]]))


#: ``task.kind`` -> its model
TASKS: dict[str, type[Model]] = {"crank-rocker": CrankRockerTask, "slider-crank": SliderCrankTask,
                                 "function": FunctionTask, "motion": MotionTask, "path": PathTask,
                                 "burmester": BurmesterTask}


#: a validated ``[task]`` table, one of :data:`TASKS`' models (a spec of :func:`spec_model` holds its kind's only)
Task = CrankRockerTask | SliderCrankTask | FunctionTask | MotionTask | PathTask | BurmesterTask


class SynthesisSpec(Model):
    """A validated synthesis template: its name, the task, and the ``[parts]`` every candidate's template gets."""

    name: str = name_field("synthesis")
    task: Task
    parts: PartsTable | None = None


@functools.cache
def spec_model(kind: str) -> type[SynthesisSpec]:
    """The :class:`SynthesisSpec` of tasks of ``kind`` (made once a kind)."""
    return create_model(f"{TASKS[kind].__name__}Spec", __base__=SynthesisSpec, task=(TASKS[kind], ...))


def validate_task(raw: Mapping[str, Any]) -> SynthesisSpec:
    """The spec of a raw synthesis template, or a one-line :class:`SpecError` naming the field."""
    if "linkage" in raw:
        raise SpecError("this is a linkage template, not a task: use `linkgen analyze` or `linkgen build`",
                        "template")
    if "sweep" in raw:
        raise SpecError("a synthesis template has no [sweep] table", "sweep")
    task = raw.get("task")
    kind = task.get("kind") if isinstance(task, Mapping) else None
    if kind is None:
        where = "task.kind" if isinstance(task, Mapping) else "task"
        raise SpecError(f"missing: give the task's kind, one of {', '.join(TASKS)}", where)
    return validate(spec_model(choose(kind, TASKS, "task.kind")), raw)


def load_task(path: str | Path, overrides: Iterable[str] = ()) -> SynthesisSpec:
    """Read a TOML synthesis template, merge ``key=value`` overrides, validate.

    Parameters
    ----------
    path : str or Path
        The task's template: a ``[task]`` table whose ``kind`` is ``crank-rocker``, ``slider-crank``,
        ``function``, ``motion`` or ``path``, and the ``[parts]`` every candidate gets.
    overrides : iterable of str
        ``"key=value"`` strings, as ``--set`` takes them.

    Returns
    -------
    SynthesisSpec
        The validated task.

    Raises
    ------
    SpecError
        The file cannot be read, is not a task, or fails validation (one line naming the key).
    """
    return validate_task(read_template(path, overrides))
