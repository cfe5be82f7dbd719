"""Any planar linkage as joints, links and sliders: its mobility and its solve order (dyad by dyad).

The user draws the linkage once (the *drawing*): every point has coordinates in mm there.
Links are rigid sets of points (a bar has two, a plate three or more); a point that two or
more bodies share is a revolute joint. ``ground`` is the fixed link. A slider is a prismatic
joint: its ``point`` moves along a straight guide fixed in the ``guide`` link, through the
point's drawn position at ``angle`` (degrees counter-clockwise from +X in the drawing); the
sliding body is ``link`` if given (it keeps its angle to the guide), else a block named
after the slider that pivots on ``point``. Inputs turn a link about one of its points
(:class:`Input` ``crank``) or move a slider (``slide``).

Every body's pose is a rotation phi and a translation T from the drawing:
``world(x) = R(phi) x + T`` for any drawn point x, so the drawing is the pose phi = 0, T = 0.

Mobility (Gruebler-Kutzbach): M = 3 (n - 1) - 2 j1 - j2, n bodies with the ground and the blocks,
j1 revolute pairs (a point shared by k bodies is k - 1 of them) plus prismatic joints, j2 the higher
pairs: gear pairs and racks (:class:`Gear`, :class:`Rack`), each of which removes one freedom.
:func:`plan` finds the solve order: inputs first, then dyads, each of two bodies that have one
unknown each (turning about a known point, or sliding along a known guide) and meet at a
joint of their own. Where none is left and bodies remain, it says why: too few inputs
(under-constrained), too many constraints (over-constrained), or a group of a higher class
than dyads (named with its joints). A higher pair is a :class:`GearStep`: it places one of its
two links from the other (and their centres) in closed form, before any dyad that could use that link.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Literal

from camgen.core.errors import SpecError
from functools import cached_property

GROUND = "ground"
#: two drawn points closer than this (relative to the drawing's size) are one point
COINCIDENT = 1e-9


@dataclass(frozen=True)
class Slider:
    """A prismatic joint: ``point`` slides along a line of ``guide`` drawn at ``angle`` (rad) through the point's
    drawn position; the sliding body is ``link``, or a block called ``name`` when link is None."""

    name: str
    point: str
    guide: str
    angle: float
    link: str | None = None

    @property
    def body(self) -> str:
        """The sliding body's name."""
        return self.link or self.name


@dataclass(frozen=True)
class Gear:
    """A gear pair, a higher pair: a gear fixed to ``bodies[0]`` about its joint ``centres[0]`` meshing with one fixed
    to ``bodies[1]`` about ``centres[1]`` (either may be the ground). Turns from the drawing (rad, counter-clockwise)
    keep ``phi_1 - phi_L = ratio (phi_0 - phi_L)``, phi_L the turn of the line of centres (of the carrier, the body
    holding both centres, where there is one): ``ratio`` is -z0 / z1 for an external pair, +z0 / z1 for an internal
    one (bodies[1] the ring); ``teeth`` (z0, z1) and ``distance`` (mm), the centre distance the teeth mesh at."""

    name: str
    bodies: tuple[str, str]
    centres: tuple[str, str]
    teeth: tuple[int, int]
    internal: bool
    distance: float

    @property
    def turns(self) -> Fraction:
        """:attr:`ratio` as an exact fraction."""
        return Fraction(self.teeth[0], self.teeth[1]) * (1 if self.internal else -1)

    @property
    def ratio(self) -> float:
        """bodies[1]'s turn relative to the line of centres per bodies[0]'s."""
        return float(self.turns)


@dataclass(frozen=True)
class Rack:
    """A rack and pinion, a higher pair: a rack fixed to slider ``slider``'s sliding body meshing with a pinion fixed
    to ``pinion`` about its joint ``centre``, which the slider's guide body holds. The rack's travel t (mm along the
    guide from the drawing, relative to the guide) and the pinion's turn psi relative to the guide (rad,
    counter-clockwise) keep ``t = lead psi``: ``lead`` is the pinion's pitch radius, positive where its centre lies
    to the left of the guide's direction (the rack's pitch line below it, seen along the guide)."""

    name: str
    slider: str
    pinion: str
    centre: str
    lead: float


Pair = Gear | Rack


@dataclass(frozen=True)
class Input:
    """An input: ``crank`` turns ``link`` about its point ``pivot`` relative to ``relative_to``; the input's value
    is the direction (rad, counter-clockwise) of the line from the pivot to the link's first other point,
    measured from +X for the ground, else from the same line of ``relative_to``. ``slide`` moves ``slider``; its
    value is the point's displacement (mm) along the guide from the drawing."""

    kind: Literal["crank", "slide"]
    link: str = ""
    pivot: str = ""
    relative_to: str = GROUND
    slider: str = ""


@dataclass(frozen=True)
class Pin:
    """A body turning about ``point``, which a known ``body`` holds."""

    point: str
    body: str


@dataclass(frozen=True)
class Slide:
    """A body sliding along slider ``slider`` on a known ``body``; ``moving`` when it is the slider's sliding body
    (else it carries the guide)."""

    slider: str
    body: str
    moving: bool


Attachment = Pin | Slide


@dataclass(frozen=True)
class InputStep:
    """Place body ``body`` by input number ``index``."""

    index: int
    body: str


@dataclass(frozen=True)
class DyadStep:
    """Place two bodies, each with one attachment to known bodies, that meet at ``joint``: a point both hold
    (revolute, ``prismatic`` False) or a slider between them (``prismatic`` True)."""

    bodies: tuple[str, str]
    attachments: tuple[Attachment, Attachment]
    joint: str
    prismatic: bool

    @property
    def kind(self) -> str:
        """The Assur name: R for a revolute, P for a prismatic joint, outer - inner - outer."""
        outer = ["R" if isinstance(a, Pin) else "P" for a in self.attachments]
        return outer[0] + ("P" if self.prismatic else "R") + outer[1]


@dataclass(frozen=True)
class FixedStep:
    """Place a body held by two attachments at once (two pins, or a pin and a slide): one constraint more than it
    needs, which :class:`Plan` lists as redundant."""

    body: str
    attachments: tuple[Attachment, Attachment]


@dataclass(frozen=True)
class Redundant:
    """A constraint no step used: the bodies ``bodies`` meeting at point ``name`` (``slider`` False), or slider
    ``name``. Checked over the motion: a paradoxical linkage when it always holds, else an over-constrained one."""

    name: str
    bodies: tuple[str, ...]
    slider: bool


@dataclass(frozen=True)
class GroupStep:
    """Place an Assur group of a class above II (no dyad order solves it): ``bodies`` held among themselves and to
    known bodies by as many constraints as they have freedoms, solved together by Newton's method with continuation
    along the input (:mod:`linkgen.kinematics.groups`). ``pins`` are its revolute pairs (point, a body of the group,
    the other body: of the group or known), ``sliders`` its prismatic joints' names."""

    bodies: tuple[str, ...]
    pins: tuple[tuple[str, str, str], ...]
    sliders: tuple[str, ...]

    @property
    def kind(self) -> str:
        """'triad' for a group of four bodies (the class-III group: a ternary link and three binary ones), else
        'group'."""
        return "triad" if len(self.bodies) == 4 else "group"

    @property
    def joints(self) -> tuple[str, ...]:
        """Its revolutes and sliders, by name (sorted)."""
        return tuple(sorted({p for p, _, _ in self.pins} | set(self.sliders)))


@dataclass(frozen=True)
class GearStep:
    """Place ``body`` by the higher pair ``pair`` (a :class:`Gear` or a :class:`Rack`) from its other member's body
    ``partner``, already placed: the body turns about its gear's centre on a known body (``attachment`` a
    :class:`Pin`), or slides along the rack's slider on its known guide (a :class:`Slide`); ``rack`` for a rack
    and pinion."""

    pair: str
    body: str
    partner: str
    attachment: Attachment
    rack: bool = False

    @property
    def kind(self) -> str:
        """'gear' or 'rack'."""
        return "rack" if self.rack else "gear"


Step = InputStep | DyadStep | FixedStep | GroupStep | GearStep


@dataclass(frozen=True)
class Structure:
    """A linkage as bodies: ``points`` (drawn, mm), ``bodies`` (name -> its points; the ground first, then the
    links in the user's order, then the blocks), ``sliders`` and ``inputs``."""

    points: Mapping[str, tuple[float, float]]
    bodies: Mapping[str, tuple[str, ...]]
    sliders: tuple[Slider, ...]
    inputs: tuple[Input, ...]
    scale: float = field(default=1.0)
    #: the higher pairs: gear pairs and racks
    gears: tuple[Gear, ...] = ()
    racks: tuple[Rack, ...] = ()

    @cached_property
    def size(self) -> float:
        """The drawing's own size (mm): the largest distance between two of its points (at least 1e-9 mm), the
        same wherever the drawing sits (``scale``, the largest coordinate, is not)."""
        xy = list(self.points.values())
        return max([1e-9] + [math.dist(a, b) for i, a in enumerate(xy) for b in xy[i + 1:]])

    @property
    def slider_by_name(self) -> dict[str, Slider]:
        return {s.name: s for s in self.sliders}

    def holders(self, point: str) -> tuple[str, ...]:
        """The bodies holding ``point``, in body order."""
        return self._holders.get(point, ())

    @cached_property
    def _holders(self) -> dict[str, tuple[str, ...]]:
        out: dict[str, list[str]] = {}
        for body, pts in self.bodies.items():
            for p in pts:
                out.setdefault(p, []).append(body)
        return {p: tuple(b) for p, b in out.items()}

    @property
    def revolutes(self) -> dict[str, tuple[str, ...]]:
        """Each point held by two or more bodies -> those bodies."""
        return {p: h for p in self.points if len(h := self.holders(p)) >= 2}

    @property
    def mobility(self) -> int:
        """Gruebler-Kutzbach: 3 (n - 1) - 2 j1 - j2 for n bodies, j1 full pairs and j2 higher pairs (gears, racks)."""
        pairs = sum(len(h) - 1 for h in self.revolutes.values()) + len(self.sliders)
        return 3 * (len(self.bodies) - 1) - 2 * pairs - len(self.gears) - len(self.racks)

    @property
    def pairs(self) -> tuple[Pair, ...]:
        """The higher pairs: the gear pairs, then the racks."""
        return (*self.gears, *self.racks)

    def carrier(self, gear: Gear) -> str | None:
        """The body holding both of a gear pair's centres (its carrier: the line of centres turns with it), if
        any."""
        return next((b for b in self.holders(gear.centres[0]) if gear.centres[1] in self.bodies[b]), None)


def make_structure(points: Mapping[str, tuple[float, float]], links: Mapping[str, tuple[str, ...]],
                   ground: tuple[str, ...], sliders: tuple[Slider, ...], inputs: tuple[Input, ...],
                   gears: tuple[Gear, ...] = (), racks: tuple[Rack, ...] = ()) -> Structure:
    """Check the names and the drawing and gather the bodies; a :class:`SpecError` naming the field otherwise."""
    if not points:
        raise SpecError("missing: give each joint's drawn position, e.g. A = [0, 0]", "linkage.joints")
    for name, xy in points.items():
        if not all(math.isfinite(v) for v in xy):
            raise SpecError(f"must be finite coordinates in mm (got {list(xy)})", f"linkage.joints.{name}")
    scale = max(1.0, max(abs(v) for xy in points.values() for v in xy))
    if GROUND in links:
        raise SpecError("'ground' is the fixed link: list its joints in linkage.ground", f"linkage.links.{GROUND}")
    bodies: dict[str, tuple[str, ...]] = {GROUND: tuple(ground)}
    for name, pts in links.items():
        bodies[name] = tuple(pts)
    for slider in sliders:
        if slider.link is None:
            if slider.name in bodies:
                raise SpecError(f"the slider's block would be called {slider.name!r}, which names a link already; "
                                "rename the slider or give link = the sliding link", f"linkage.sliders.{slider.name}")
            bodies[slider.name] = (slider.point,)
    for body, pts in bodies.items():
        where = "linkage.ground" if body == GROUND else f"linkage.links.{body}"
        if body != GROUND and not pts:
            raise SpecError("a link needs at least one joint", where)
        for p in pts:
            if p not in points:
                raise SpecError(f"no joint {p!r}: give its position in [linkage.joints] "
                                f"(joints: {', '.join(points)})", where)
        if len(set(pts)) != len(pts):
            raise SpecError("a joint is listed twice", where)
        for i, a in enumerate(pts):
            for b in pts[i + 1:]:
                if math.dist(points[a], points[b]) <= COINCIDENT * scale:
                    raise SpecError(f"joints {a} and {b} are drawn at the same place: the link between them has no "
                                    "length", where)
    for slider in sliders:
        where = f"linkage.sliders.{slider.name}"
        if slider.guide not in bodies:
            raise SpecError(f"no link {slider.guide!r} to guide it (links: {', '.join(bodies)})", f"{where}.guide")
        if slider.link is not None and slider.link not in bodies:
            raise SpecError(f"no link {slider.link!r} (links: {', '.join(bodies)})", f"{where}.link")
        if slider.point not in bodies[slider.body]:
            raise SpecError(f"the sliding link {slider.body!r} does not hold {slider.point!r}", f"{where}.point")
        if slider.body == slider.guide:
            raise SpecError("a link cannot slide on itself", f"{where}.guide")
        if not math.isfinite(slider.angle):
            raise SpecError("must be a finite angle in degrees", f"{where}.angle")
    structure = Structure(points, bodies, tuple(sliders), tuple(inputs), scale, tuple(gears), tuple(racks))
    _check_pairs(structure)
    _check_held(structure)
    _check_inputs(structure)
    _check_input_count(structure)
    _check_connected(structure)
    return structure


#: how closely (mm) a gear pair's centres, or a pinion's centre and its rack's pitch line, must lie at the distance
#: their teeth mesh at
MESH_TOL_MM = 1e-6


def _check_pairs(s: Structure) -> None:
    """Refuse a gear on a link that does not hold its centre, two gears on one link, a rack on no slider or with its
    pinion's centre off the guide's body, and members drawn other than at the distance their teeth mesh at."""
    for g in s.gears:
        where = f"linkage.gears.{g.name}"
        for key, body, centre in zip("ab", g.bodies, g.centres, strict=True):
            if body not in s.bodies:
                raise SpecError(f"no link {body!r} (links: {', '.join(s.bodies)})", f"{where}.{key}.link")
            if centre not in s.bodies[body]:
                raise SpecError(f"link {body!r} does not hold {centre!r}: a gear turns with its link about one of "
                                f"its joints ({', '.join(s.bodies[body])})", f"{where}.{key}.centre")
        if g.bodies[0] == g.bodies[1]:
            raise SpecError("the two gears of a pair are on one link: they could not turn", f"{where}.b.link")
        if g.centres[0] == g.centres[1] and not g.internal:
            raise SpecError("an external pair's centres are one joint: give each gear its own centre",
                            f"{where}.b.centre")
        got = math.dist(s.points[g.centres[0]], s.points[g.centres[1]])
        if abs(got - g.distance) > MESH_TOL_MM:
            raise SpecError(f"the drawing puts the centres {g.centres[0]} and {g.centres[1]} {got:.9g} mm apart, but "
                            f"teeth {g.teeth[0]} and {g.teeth[1]} mesh at {g.distance:.9g} mm (m (z1 "
                            f"{'-' if g.internal else '+'} z2) / 2, within {MESH_TOL_MM:g} mm): move a centre",
                            where)
    sliders = s.slider_by_name
    for r in s.racks:
        where = f"linkage.racks.{r.name}"
        if r.slider not in sliders:
            raise SpecError(f"a rack rides on a slider: no slider {r.slider!r} (sliders: "
                            f"{', '.join(sliders) or 'none'})", f"{where}.slider")
        if r.pinion not in s.bodies:
            raise SpecError(f"no link {r.pinion!r} (links: {', '.join(s.bodies)})", f"{where}.pinion.link")
        sl = sliders[r.slider]
        if r.centre not in s.bodies[r.pinion]:
            raise SpecError(f"link {r.pinion!r} does not hold {r.centre!r}", f"{where}.pinion.centre")
        if r.centre not in s.bodies[sl.guide] or r.pinion in (sl.guide, sl.body):
            raise SpecError(f"the pinion turns about a joint of the rack's guide {sl.guide!r} (its joints: "
                            f"{', '.join(s.bodies[sl.guide])}), on a link of its own", f"{where}.pinion.centre")


def _check_held(s: Structure) -> None:
    """Refuse a drawn point on no body (a link, the ground or a slider's block): it would be drawn and then
    ignored, and a tracer on none has no path."""
    held = {p for pts in s.bodies.values() for p in pts}
    for name in s.points:
        if name not in held:
            raise SpecError(f"joint {name} is on no link: list it in a link of linkage.links (a tracer too: the "
                            "link it moves with) or in linkage.ground, or remove it", f"linkage.joints.{name}")


def _check_input_count(s: Structure) -> None:
    """Refuse more than one input where Gruebler's mobility is less than their count: one input of a mobility-1
    linkage sets every pose, and a second would pull it apart (one input of a linkage of mobility 0 or less is
    kept: a paradoxical linkage moves, which the motion's check of its redundant constraints decides)."""
    mobility, count = s.mobility, len(s.inputs)
    if count <= 1 or count <= mobility:
        return
    if mobility <= 0:
        raise SpecError(f"mobility {mobility} (Gruebler): a structure, or a paradoxical linkage that one input may "
                        f"move, not {count} inputs: give one input", "linkage.input")
    raise SpecError(f"mobility {mobility} (Gruebler) takes {mobility} input{'s' if mobility > 1 else ''}, not "
                    f"{count}: give {'one input (not a list)' if mobility == 1 else f'{mobility} inputs'}",
                    "linkage.input")


def _check_inputs(s: Structure) -> None:
    if not s.inputs:
        raise SpecError("missing: give the input, e.g. input = {link = \"crank\", pivot = \"O\"}", "linkage.input")
    sliders = s.slider_by_name
    for i, inp in enumerate(s.inputs):
        where = "linkage.input" if len(s.inputs) == 1 else f"linkage.input[{i}]"
        if inp.kind == "slide":
            if inp.slider not in sliders:
                raise SpecError(f"no slider {inp.slider!r} (sliders: {', '.join(sliders) or 'none'})",
                                f"{where}.slider")
            continue
        if inp.link not in s.bodies or inp.link == GROUND:
            raise SpecError(f"no moving link {inp.link!r} (links: {', '.join(list(s.bodies)[1:])})", f"{where}.link")
        if inp.pivot not in s.bodies[inp.link]:
            raise SpecError(f"link {inp.link!r} does not hold {inp.pivot!r}", f"{where}.pivot")
        if len(s.bodies[inp.link]) < 2:
            raise SpecError(f"link {inp.link!r} needs a second joint to show its angle", f"{where}.link")
        if inp.relative_to not in s.bodies or inp.pivot not in s.bodies[inp.relative_to]:
            raise SpecError(f"must name a link that holds the pivot {inp.pivot!r} too", f"{where}.relative_to")
        if inp.relative_to != GROUND and len(s.bodies[inp.relative_to]) < 2:
            raise SpecError(f"link {inp.relative_to!r} needs a second joint to measure the angle from",
                            f"{where}.relative_to")
    driven = [inp.link if inp.kind == "crank" else sliders[inp.slider].body for inp in s.inputs]
    for body in driven:
        if driven.count(body) > 1:
            raise SpecError(f"link {body!r} is driven by two inputs", "linkage.input")


def _check_connected(s: Structure) -> None:
    """Every body reaches the ground through joints and sliders."""
    reached, frontier = {GROUND}, [GROUND]
    neighbours: dict[str, set[str]] = {b: set() for b in s.bodies}
    for holders in s.revolutes.values():
        for b in holders:
            neighbours[b].update(holders)
    for slider in s.sliders:
        neighbours[slider.body].add(slider.guide)
        neighbours[slider.guide].add(slider.body)
    while frontier:
        for n in neighbours[frontier.pop()] - reached:
            reached.add(n)
            frontier.append(n)
    loose = [b for b in s.bodies if b not in reached]
    if loose:
        raise SpecError(f"link{'s' if len(loose) > 1 else ''} {', '.join(loose)} "
                        f"{'are' if len(loose) > 1 else 'is'} not joined to the rest: share a joint with another "
                        "link", "linkage.links")


@dataclass(frozen=True)
class Plan:
    """The solve order (input, dyad and fixed steps), the redundant constraints to check, and the mobility."""

    steps: tuple[Step, ...]
    redundant: tuple[Redundant, ...]
    mobility: int


def _attachments(s: Structure, body: str, known: set[str]) -> list[Attachment]:
    """How ``body`` is held by known bodies: a pin at each point it shares with one, a slide on each slider to
    one."""
    out: list[Attachment] = []
    for p in s.bodies[body]:
        holder = next((b for b in s.holders(p) if b in known and b != body), None)
        if holder is not None:
            out.append(Pin(p, holder))
    for slider in s.sliders:
        if slider.body == body and slider.guide in known:
            out.append(Slide(slider.name, slider.guide, True))
        elif slider.guide == body and slider.body in known:
            out.append(Slide(slider.name, slider.body, False))
    return out


def _joints_between(s: Structure, a: str, b: str, used: set[str]) -> list[tuple[str, bool]]:
    """Joints between bodies a and b, (name, prismatic), not among ``used`` points (the attachments')."""
    out = [(p, False) for p in s.bodies[a] if p in s.bodies[b] and p not in used]
    out += [(sl.name, True) for sl in s.sliders if {sl.body, sl.guide} == {a, b}]
    return out


def plan(s: Structure) -> Plan:
    """The order in which the bodies are placed, or a :class:`SpecError` saying why they cannot be."""
    known = {GROUND}
    steps: list[Step] = []
    pending = list(enumerate(s.inputs))
    while True:
        ready = next(((k, i, inp) for k, (i, inp) in enumerate(pending) if _reference(s, inp) in known), None)
        if ready is not None:
            k, index, inp = ready
            steps.append(InputStep(index, _driven(s, inp)))
            known.add(_driven(s, inp))
            del pending[k]
            continue
        driven = {_driven(s, inp) for _, inp in pending}
        geared = _find_gear(s, known, driven, {st.pair for st in steps if isinstance(st, GearStep)})
        if geared is not None:
            steps.append(geared)
            known.add(geared.body)
            continue
        unknown = [b for b in s.bodies if b not in known and b not in driven]
        held = {b: _attachments(s, b, known) for b in unknown}
        dyad = _find_dyad(s, unknown, held)
        if dyad is None:
            fixed = next((b for b in unknown if len(held[b]) >= 2
                          and not all(isinstance(a, Slide) for a in held[b][:2])), None)
            if fixed is None:
                group = _find_group(s, unknown, known)
                if group is None:
                    break
                steps.append(group)
                known.update(group.bodies)
                continue
            steps.append(FixedStep(fixed, (held[fixed][0], held[fixed][1])))
            known.add(fixed)
        else:
            steps.append(dyad)
            known.update(dyad.bodies)
    unknown = [b for b in s.bodies if b not in known]
    if unknown or pending:
        _diagnose(s, unknown, [inp for _, inp in pending])
    _check_pairs_used(s, steps)
    mobility = s.mobility
    if mobility > len(s.inputs):
        raise SpecError(f"mobility {mobility} (Gruebler) but {len(s.inputs)} input(s): the linkage would move "
                        "freely; add an input or a link", "linkage.input")
    return Plan(tuple(steps), _redundant(s, steps), mobility)


def _find_gear(s: Structure, known: set[str], driven: set[str], used: set[str]) -> GearStep | None:
    """The first higher pair not yet used that places a body from its placed partner: a gear whose centre a known
    body holds, or a rack (from its pinion) or a pinion (from its rack) once the rack's guide is known; None if no
    pair can."""
    for g in s.gears:
        if g.name in used:
            continue
        for k in (0, 1):
            body, partner, centre = g.bodies[1 - k], g.bodies[k], g.centres[1 - k]
            if partner not in known or body in known or body in driven:
                continue
            holder = next((b for b in s.holders(centre) if b in known and b != body), None)
            if holder is not None:
                return GearStep(g.name, body, partner, Pin(centre, holder))
    sliders = s.slider_by_name
    for r in s.racks:
        sl = sliders[r.slider]
        if r.name in used or sl.guide not in known:
            continue
        if r.pinion in known and sl.body not in known and sl.body not in driven:
            return GearStep(r.name, sl.body, r.pinion, Slide(sl.name, sl.guide, True), True)
        if sl.body in known and r.pinion not in known and r.pinion not in driven:
            return GearStep(r.name, r.pinion, sl.body, Pin(r.centre, sl.guide), True)
    return None


def _check_pairs_used(s: Structure, steps: list[Step]) -> None:
    """Refuse a higher pair no step used: both its members were placed by other joints, so it could only hold by
    chance (an over-constrained linkage)."""
    used = {st.pair for st in steps if isinstance(st, GearStep)}
    for pair in s.pairs:
        if pair.name not in used:
            where = f"linkage.gears.{pair.name}" if isinstance(pair, Gear) else f"linkage.racks.{pair.name}"
            raise SpecError(f"over-constrained (mobility {s.mobility}): the links of this pair are placed by other "
                            "joints before it, so its teeth would fight them; remove the pair or a joint", where)


def check_whole_turns(s: Structure, steps: tuple[Step, ...]) -> None:
    """With one crank input, refuse a pair that makes a link turn a fraction of a turn per turn of the input (the
    linkage would come back to its drawing only after several), or a rack run away from it (its pinion turning
    fully). Turns per input turn are followed exactly along the inputs and the pairs; a body placed by a dyad turns
    a whole number of times (unknown here), so a pair from it is refused only when its ratio is sure to break that.
    (:meth:`~linkgen.kinematics.linkage.Linkage.solve` reads a crank's input on one turn from the drawing: input
    values within that turn are right whatever the ratio.)"""
    if len(s.inputs) != 1 or s.inputs[0].kind != "crank":
        return
    turns: dict[str, Fraction | None] = {GROUND: Fraction(0)}
    for step in steps:
        if isinstance(step, InputStep):
            ref = turns.get(s.inputs[0].relative_to)
            turns[step.body] = None if ref is None else ref + 1
        elif isinstance(step, GearStep):
            pair = next(p for p in s.pairs if p.name == step.pair)
            turns[step.body] = _geared_turns(s, step, pair, turns)
        else:
            for body in (step.bodies if isinstance(step, (DyadStep, GroupStep)) else (step.body,)):
                turns[body] = None


def _geared_turns(s: Structure, step: GearStep, pair: Pair, turns: dict[str, Fraction | None]) -> Fraction | None:
    """The turns per input turn of the body a gear step places (None where not known: a whole number), or a
    :class:`SpecError` where they are not whole."""
    partner = turns.get(step.partner)
    if isinstance(pair, Rack):
        guide = turns.get(s.slider_by_name[pair.slider].guide)
        if step.body != pair.pinion and partner is not None and guide is not None and partner != guide:
            raise SpecError(f"the crank turns pinion {pair.pinion} fully, so the rack would run away along its "
                            "guide; drive the slider (input = { slider = ... }) or move the rack from a link that "
                            "swings", f"linkage.racks.{pair.name}")
        return guide
    carrier = s.carrier(pair)
    line = turns.get(carrier) if carrier is not None else None
    ratio = pair.turns if step.body == pair.bodies[1] else 1 / pair.turns
    if partner is None or line is None:
        return None
    got = line + ratio * (partner - line)
    if got.denominator != 1:
        raise SpecError(f"with the crank input, link {step.body} turns {got} times a turn of the input, so the linkage "
                        f"comes back to its drawing only after {got.denominator} turns, which is not analysed; "
                        f"drive link {step.body} instead or give teeth in a whole ratio", f"linkage.gears.{pair.name}")
    return got


def _reference(s: Structure, inp: Input) -> str:
    """The body an input is measured from."""
    return inp.relative_to if inp.kind == "crank" else s.slider_by_name[inp.slider].guide


def _driven(s: Structure, inp: Input) -> str:
    """The body an input moves."""
    return inp.link if inp.kind == "crank" else s.slider_by_name[inp.slider].body


def _redundant(s: Structure, steps: list[Step]) -> tuple[Redundant, ...]:
    """The constraints no step used: at each shared point, the holders the used pins leave unconnected; each
    slider no step used."""
    used: dict[str, list[tuple[str, str]]] = {p: [] for p in s.revolutes}
    used_sliders: set[str] = set()

    def use(body: str, attachment: Attachment) -> None:
        if isinstance(attachment, Pin):
            used[attachment.point].append((body, attachment.body))
        else:
            used_sliders.add(attachment.slider)

    for step in steps:
        if isinstance(step, InputStep):
            inp = s.inputs[step.index]
            if inp.kind == "crank":
                used[inp.pivot].append((inp.link, inp.relative_to))
            else:
                used_sliders.add(inp.slider)
        elif isinstance(step, DyadStep):
            for body, attachment in zip(step.bodies, step.attachments, strict=True):
                use(body, attachment)
            if step.prismatic:
                used_sliders.add(step.joint)
            else:
                used[step.joint].append(step.bodies)
        elif isinstance(step, GroupStep):
            for point, a, b in step.pins:
                used[point].append((a, b))
            used_sliders.update(step.sliders)
        elif isinstance(step, GearStep):
            use(step.body, step.attachment)
        else:
            use(step.body, step.attachments[0])     # the second attachment is the one too many: checked
    out = []
    for point, holders in s.revolutes.items():
        group = {h: h for h in holders}

        def root(x: str, group: dict = group) -> str:
            while group[x] != x:
                x = group[x]
            return x

        for a, b in used[point]:
            group[root(a)] = root(b)
        for h in holders[1:]:
            if root(h) != root(holders[0]):
                out.append(Redundant(point, (holders[0], h), False))
                group[root(h)] = root(holders[0])
    out += [Redundant(sl.name, (sl.body, sl.guide), True) for sl in s.sliders if sl.name not in used_sliders]
    return tuple(out)


def _find_group(s: Structure, unknown: list[str], known: set[str]) -> GroupStep | None:
    """The smallest set of unknown bodies (3 to :data:`GROUP_BODIES`) held among themselves and to known bodies by
    exactly as many pairs as they have freedoms (an Assur group: no smaller set is, or a dyad would have been
    found); None if there is none."""
    from itertools import combinations

    for size in range(3, min(GROUP_BODIES, len(unknown)) + 1):
        for group in combinations(unknown, size):
            pins, sliders = _group_pairs(s, set(group), known)
            if 3 * size == 2 * (len(pins) + len(sliders)):
                return GroupStep(tuple(group), pins, sliders)
    return None


#: the most bodies :func:`_find_group` puts in one group (a triad has 4; class IV groups 6)
GROUP_BODIES = 6


def _group_pairs(s: Structure, group: set[str], known: set[str]
                 ) -> tuple[tuple[tuple[str, str, str], ...], tuple[str, ...]]:
    """The pairs holding ``group`` among themselves and to ``known`` bodies: at each shared point, its holders in
    the group each joined to the first holder (a known one first, as one body); the sliders between them."""
    pins = []
    for point, holders in s.revolutes.items():
        mine = [b for b in holders if b in group]
        anchor = next((b for b in holders if b in known), None)
        if not mine or (anchor is None and len(mine) < 2):
            continue
        first = anchor if anchor is not None else mine[0]
        pins += [(point, b, first) for b in mine if b != first]
    sliders = tuple(sl.name for sl in s.sliders if {sl.body, sl.guide} & group and {sl.body, sl.guide} <= group | known)
    return tuple(pins), sliders


def _find_dyad(s: Structure, unknown: list[str], held: dict[str, list[Attachment]]) -> DyadStep | None:
    """The first pair of bodies, each held once, that meet at a joint of their own."""
    single = [b for b in unknown if len(held[b]) == 1]
    for i, a in enumerate(single):
        for b in single[i + 1:]:
            att_a, att_b = held[a][0], held[b][0]
            used = {x.point for x in (att_a, att_b) if isinstance(x, Pin)}
            for joint, prismatic in _joints_between(s, a, b, used):
                if not prismatic or not (isinstance(att_a, Slide) and isinstance(att_b, Slide)):
                    return DyadStep((a, b), (att_a, att_b), joint, prismatic)
    return None


def _diagnose(s: Structure, unknown: list[str], pending: list[Input]) -> None:
    """Why the bodies ``unknown`` cannot be placed: the count of freedoms among them (the known ones as one)."""
    if pending:
        inp = pending[0]
        what = f"link {inp.link!r}" if inp.kind == "crank" else f"slider {inp.slider!r}"
        ref = inp.relative_to if inp.kind == "crank" else s.slider_by_name[inp.slider].guide
        raise SpecError(f"the input drives {what} relative to {ref!r}, which the other inputs and links do not "
                        "place; drive a link from the ground", "linkage.input")
    merged = {b: (b if b in unknown else GROUND) for b in s.bodies}
    pairs = 0
    for holders in s.revolutes.values():
        ends = {merged[b] for b in holders}
        if any(b in unknown for b in holders):
            pairs += len(ends) - 1
    pairs += sum(1 for sl in s.sliders if merged[sl.body] != merged[sl.guide])
    higher = sum(1 for g in s.gears if merged[g.bodies[0]] != merged[g.bodies[1]])
    higher += sum(1 for r in s.racks if merged[r.pinion] != merged[s.slider_by_name[r.slider].body])
    freedom = 3 * len(unknown) - 2 * pairs - higher
    names = ", ".join(unknown)
    if freedom > 0:
        raise SpecError(f"links {names} are not fixed by the inputs (mobility {s.mobility}, {len(s.inputs)} "
                        f"input(s)): they can move {freedom} way(s) freely; add an input or a link", "linkage")
    if freedom < 0:
        raise SpecError(f"links {names} are over-constrained (mobility {s.mobility}): remove a link or a joint",
                        "linkage")
    joints = sorted({p for b in unknown for p in s.bodies[b] if len(s.holders(p)) >= 2}
                    | {sl.name for sl in s.sliders if sl.body in unknown or sl.guide in unknown})
    raise SpecError(f"links {names} form a group of a higher class than dyads (joints {', '.join(joints)}) with "
                    f"more than {GROUP_BODIES} links: linkgen solves dyads and groups of up to {GROUP_BODIES} links; "
                    "drive the linkage from another link", "linkage")
