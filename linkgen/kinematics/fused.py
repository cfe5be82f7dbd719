"""Fused kernels of the general solver: a crank followed by RRR dyads, in complex numbers, chunk by chunk.

The general solve (:func:`linkgen.kinematics.linkage._solve`) places every body step by step with a
dozen named intermediate arrays per dyad over all poses at once. For the linkages most users draw
(one crank on the ground, then RRR dyads: Jansen's and Klann's legs, Watt's and
Stephenson's six-bars) this module does the same work with

* the solve order planned once (:func:`program`, cached on the linkage): each step's drawn points,
  radii and the complex factors that turn a drawn vector into a body's rotation, as numbers;
* every pose a complex number: a body's rotation ``q = cos(phi) + i sin(phi)`` and translation
  ``T`` (mm), so ``world(x) = q x + T`` is one multiply and one add, and a point (n, 2) is the float
  view of a complex (n,) array (no copy);
* the poses cut into chunks of :data:`CHUNK` that stay in the processor's cache, each result
  written in place into its slice of the full outputs, so a long run holds only the outputs and one
  chunk's temporaries;
* the outputs made as one block of each kind (huge pages for a long run), each chunk writing only its own slices
  of them, so the chunks may be shared among threads (``workers``; one by default, :data:`WORKERS`) and the result
  does not depend on the thread count.

Signs and frames are :mod:`linkgen.kinematics.linkage`'s: an RRR's joint lies to the left of
pin 1 -> pin 2 for sign +1; velocities per unit input speed, accelerations at constant input speed.
The closed form is the same construction (Kahan's stable triangle area, the joint from the pins'
frame), so the results equal the general solve's to rounding. A linkage of any other dyad (RRP, RPR,
PRP, RPP), a fixed step, several inputs or a slide input has no program and is solved by the general
path; so is a solve where a deltoid's equal-radius pins meet (:data:`~linkgen.kinematics.linkage.FOLD_REACH`),
whose joint is placed by the motion's limit there.
"""
from __future__ import annotations

import functools
from concurrent.futures import ThreadPoolExecutor, wait
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.structure import GROUND, DyadStep, InputStep, Pin, Structure

#: poses per chunk: a complex array of this many is 128 KiB, so a dyad's few dozen temporaries stay in a core's
#: 2 MiB cache (measured on Jansen's leg: flat from 4096 to 32768, slower below)
CHUNK = 8192


#: threads a run's chunks are shared among by default: one, the calling thread. numpy releases the interpreter
#: lock inside each array operation, but a chunk's take a few microseconds each and two threads take turns at the
#: lock between them: on two free cores two threads took 1.2x to 2.7x the time of one at 10^4 poses and 1.0x to
#: 1.3x from 3 10^4 to 10^6 (Jansen's and Klann's legs, a Watt I six-bar; positions, and with rates). Where they
#: looked faster, they were sharing the page faults of outputs made as separate arrays (see :func:`allocate`)
WORKERS = 1


#: a point of a body over the poses: its body (None: the ground) and its drawn name
Key = tuple[str | None, str]


@dataclass(frozen=True)
class Frame:
    """How a body's drawn points reach the world: ``world(x) = P + a * (f * (x - pd))`` with ``P`` the world
    position of its anchor (the pin it turns about, drawn at ``pd``) and ``a`` (n,) complex the world image of the
    drawn vector 1 / f; so its rotation is ``q = a f``. ``f`` and ``pd`` are numbers, fixed by the solve order."""

    pd: complex
    f: complex

    def factor(self, xd: complex) -> complex:
        """The number k with world(x) = P + a k."""
        return self.f * (xd - self.pd)


@dataclass(frozen=True)
class CrankOp:
    """Turn ``body`` about its ground pivot ``pivot`` by input ``index`` from its drawn value ``drawn`` (rad)."""

    body: str
    pivot: str
    index: int
    drawn: float


@dataclass(frozen=True)
class RRROp:
    """An RRR dyad of step ``step``: bodies ``bodies`` pinned at drawn points ``pins`` to known ``refs`` (None: the
    ground), meeting at ``joint``; radii ``r1``, ``r2`` (mm). ``deltoid`` when the radii are equal (within
    ``fold_reach``, mm): its pins may meet."""

    step: int
    bodies: tuple[str, str]
    refs: tuple[str | None, str | None]
    pins: tuple[str, str]
    joint: str
    r1: float
    r2: float
    deltoid: bool
    fold_reach: float

    def area_squared(self, dd: np.ndarray) -> np.ndarray:
        """(4 area)^2 of the triangles of sides r1, r2 and the pins' distance sqrt(dd): ((r1 + r2)^2 - dd)
        (dd - (r1 - r2)^2), negative beyond reach. From the squared distance itself, each factor vanishing at its
        toggle to the rounding of dd and of the squared radii: as close as Kahan's stable Heron of the rounded
        distance (:func:`linkgen.kinematics.dyads.area4`), in three operations instead of twelve."""
        prod = np.subtract((self.r1 + self.r2) ** 2, dd)
        prod *= dd - (self.r1 - self.r2) ** 2
        return prod


@dataclass(frozen=True)
class Program:
    """The planned solve: its operations in order; each placed body's :class:`Frame`; each point's holder (the
    first placed body that holds it, None: the ground) and drawn position (complex, mm), and the holders by
    point."""

    ops: tuple[CrankOp | RRROp, ...]
    frames: dict[str, Frame]
    points: tuple[tuple[str, str | None, complex], ...]
    drawn: dict[str, complex]
    holders: dict[str, str | None]

    @property
    def bodies(self) -> tuple[str, ...]:
        """The moving bodies in the order they are placed."""
        return tuple(self.frames)


def _c(s: Structure, name: str) -> complex:
    x, y = s.points[name]
    return complex(float(x), float(y))


def program(s: Structure, steps: tuple[object, ...], drawn: tuple[float, ...], fold_reach: float) -> Program | None:
    """The fused program of a solve order (``drawn`` each input's drawn value, rad; ``fold_reach`` relative to the
    drawing's size), or None where it has a step the kernels do not cover (anything but one crank on the ground and RRR
    dyads)."""
    if len(s.inputs) != 1 or s.inputs[0].kind != "crank" or s.inputs[0].relative_to != GROUND:
        return None
    ops: list[CrankOp | RRROp] = []
    frames: dict[str, Frame] = {}
    for index, step in enumerate(steps):
        if isinstance(step, InputStep):
            inp = s.inputs[step.index]
            ops.append(CrankOp(step.body, inp.pivot, step.index, drawn[step.index]))
            frames[step.body] = Frame(_c(s, inp.pivot), 1.0 + 0j)
        elif isinstance(step, DyadStep) and step.kind == "RRR":
            a1, a2 = step.attachments
            if not (isinstance(a1, Pin) and isinstance(a2, Pin)):
                return None
            jd = _c(s, step.joint)
            v1, v2 = jd - _c(s, a1.point), jd - _c(s, a2.point)
            r1, r2 = abs(v1), abs(v2)
            refs = (None if a1.body == GROUND else a1.body, None if a2.body == GROUND else a2.body)
            ops.append(RRROp(index, step.bodies, refs, (a1.point, a2.point), step.joint, r1, r2,
                             abs(r1 - r2) <= fold_reach * s.size, fold_reach * s.size))
            # the drawn vector pin -> joint turns onto the world one a: q = a conj(v) / |v|^2
            frames[step.bodies[0]] = Frame(_c(s, a1.point), v1.conjugate() / (r1 * r1))
            frames[step.bodies[1]] = Frame(_c(s, a2.point), v2.conjugate() / (r2 * r2))
        else:
            return None
    points = []
    for name in s.points:
        holder = next((b for b in s.holders(name) if b == GROUND or b in frames), None)
        if holder is not None:
            points.append((name, None if holder == GROUND else holder, _c(s, name)))
    return Program(tuple(ops), frames, tuple(points), {name: _c(s, name) for name in s.points},
                   {name: holder for name, holder, _ in points})


@dataclass
class Outputs:
    """The full-length results the chunks write into: complex points (and velocities, accelerations), complex
    rotations, angular rates, each dyad's margin, transmission angle, slack and spread, and ``ok``."""

    points: dict[str, np.ndarray]
    velocities: dict[str, np.ndarray]
    accelerations: dict[str, np.ndarray]
    rotations: dict[str, np.ndarray]
    omegas: dict[str, np.ndarray]
    alphas: dict[str, np.ndarray]
    margins: list[np.ndarray]
    transmissions: list[np.ndarray]
    slacks: list[np.ndarray]
    spreads: list[np.ndarray]
    ok: np.ndarray


def allocate(prog: Program, n: int, derivatives: bool, extras: bool) -> Outputs:
    """Empty outputs for n poses (moving points only: a ground point is a constant); ``extras`` the rotations, the
    bodies' rates and the dyads' results besides the points. Each output is a row of one complex or one float block
    (a result kept keeps its block): numpy gives a block of 4 MiB or more huge pages, and the first writes to a
    fresh block fault once a 2 MiB page where separate arrays of under 4 MiB faulted once a 4 KiB one (Jansen's
    leg at 10^5 poses, one thread: 2.6 ms where it took 6.0, its outputs' faults more than its arithmetic)."""
    moving = [name for name, holder, _ in prog.points if holder is not None]
    dyads = sum(isinstance(op, RRROp) for op in prog.ops) if extras else 0
    rates = derivatives and extras
    bodies = len(prog.bodies)
    complexes = iter(np.empty((len(moving) * (3 if derivatives else 1) + (bodies if extras else 0), n), dtype=complex))
    reals = iter(np.empty(((2 * bodies if rates else 0) + dyads * (4 if derivatives else 3), n)))

    def cplx(names: list[str] | tuple[str, ...], want: bool = True) -> dict[str, np.ndarray]:
        return {k: next(complexes) for k in names} if want else {}

    def real(count: int) -> list[np.ndarray]:
        return [next(reals) for _ in range(count)]

    return Outputs(cplx(moving), cplx(moving, derivatives), cplx(moving, derivatives), cplx(prog.bodies, extras),
                   {b: next(reals) for b in prog.bodies} if rates else {},
                   {b: next(reals) for b in prog.bodies} if rates else {},
                   real(dyads), real(dyads), real(dyads), real(dyads if derivatives else 0), np.ones(n, dtype=bool))


class Folded(Exception):
    """A deltoid's equal-radius pins meet in this solve: the general path places its joint by the motion."""


def run(prog: Program, x: np.ndarray, rates: np.ndarray, signs: list[np.ndarray] | list[float], derivatives: bool,
        extras: bool, feasibility_tol: float, workers: int | None = None, chunk: int | None = None) -> Outputs:
    """Every chunk of the poses ``x`` (k, n) through the program (``signs`` each step's branch, a number or one a
    pose), the chunks (of ``chunk`` poses, default :data:`CHUNK`) shared among ``workers`` threads (default
    :data:`WORKERS`) in contiguous runs, each chunk writing only its own slice of the outputs, so that the result
    does not depend on either; raises :class:`Folded` where the general path must place a deltoid."""
    n = x.shape[1]
    size = CHUNK if chunk is None else int(chunk)
    out = allocate(prog, n, derivatives, extras)
    rows = [g if np.ndim(g) == 0 else np.broadcast_to(np.asarray(g, dtype=float), (n,)) for g in signs]
    starts = list(range(0, n, size))
    threads = max(1, min(WORKERS if workers is None else int(workers), len(starts)))
    # numpy's floating-point error state is per thread (a context variable): the caller's goes with each task
    err = np.geterr()

    def chunks(part: list[int]) -> None:
        with np.errstate(**err):
            for start in part:
                _Chunk(prog, slice(start, min(n, start + size)), rates, derivatives, extras, out).run(
                    x, rows, feasibility_tol)

    if threads == 1:
        chunks(starts)
        return out
    share = -(-len(starts) // threads)
    parts = [starts[i:i + share] for i in range(0, len(starts), share)]
    tasks = [_pool(threads).submit(chunks, part) for part in parts]
    wait(tasks)                        # every task done before a task's Folded (or any error) is raised here
    for task in tasks:
        task.result()
    return out


@functools.cache
def _pool(threads: int) -> ThreadPoolExecutor:
    """The threads of :func:`run` for ``threads`` workers, started once per process and kept (idle threads cost
    nothing; starting them costs about as much as a short run)."""
    return ThreadPoolExecutor(max_workers=threads, thread_name_prefix="linkgen-fused")


class _Chunk:
    """One chunk of poses through the program: each placed body's anchor P and vector a (and, with derivatives,
    its anchor's velocity vP and acceleration aP, and the factors i w and -w^2 + i al that take a radius vector from
    the anchor to its point's velocity and acceleration about it), the ground's as numbers; each point computed
    once, with its radius vector from its body's anchor."""

    def __init__(self, prog: Program, sl: slice, rates: np.ndarray, derivatives: bool, extras: bool,
                 out: Outputs) -> None:
        self.prog, self.sl, self.rates, self.derivatives, self.extras, self.out = (prog, sl, rates, derivatives,
                                                                                  extras, out)
        self.m = sl.stop - sl.start
        self.P: dict[str, np.ndarray | complex] = {}
        self.a: dict[str, np.ndarray] = {}
        self.vP: dict[str, np.ndarray | complex] = {}
        self.aP: dict[str, np.ndarray | complex] = {}
        self.iw: dict[str, np.ndarray | complex] = {}
        self.spin: dict[str, np.ndarray | complex] = {}
        self.known: dict[Key, np.ndarray | complex] = {}
        self.radius: dict[Key, np.ndarray | None] = {}
        self.moving: dict[Key, tuple[np.ndarray | complex, np.ndarray | complex]] = {}
        #: a body whose vector ``a`` is not made yet: the world points (J, p) it runs between, a = J - p
        self.later: dict[str, tuple[np.ndarray, np.ndarray | complex]] = {}
        #: whether every input and every dyad's 2x2 determinant is finite and non-zero: then no rate is NaN
        self.finite = True

    def dest(self, body: str, name: str) -> np.ndarray | None:
        """The output slice of point ``name`` where ``body`` is the one that places it (else None)."""
        if self.prog.holders.get(name) != body:
            return None
        return self.out.points[name][self.sl]

    def point(self, body: str | None, name: str) -> np.ndarray | complex:
        """World position of drawn point ``name`` on ``body`` (a number on the ground), written straight into its
        output where ``body`` places it."""
        key = (body, name)
        if key not in self.known:
            if body is None:
                self.known[key] = self.prog.drawn[name]
            else:
                r = self.vector(body) * self.prog.frames[body].factor(self.prog.drawn[name])
                self.radius[key] = r
                self.known[key] = np.add(r, self.P[body], out=self.dest(body, name))
        return self.known[key]

    def vector(self, body: str) -> np.ndarray:
        """The body's vector ``a`` (see :class:`Frame`), made on first use where its dyad left it for later."""
        if body not in self.a:
            jw, p = self.later.pop(body)
            self.a[body] = np.subtract(jw, p)
        return self.a[body]

    def place(self, body: str, name: str, xw: np.ndarray | complex, r: np.ndarray | None) -> None:
        """Record ``name`` on ``body`` at world xw, radius vector r from the body's anchor (None: the anchor)."""
        self.known[(body, name)] = xw
        self.radius[(body, name)] = r

    def rates_of(self, body: str | None, name: str) -> tuple[np.ndarray | complex, np.ndarray | complex]:
        """Velocity and acceleration of point ``name`` on ``body`` (zero on the ground), computed once."""
        if body is None:
            return 0j, 0j
        key = (body, name)
        if key not in self.moving:
            self.point(body, name)
            r = self.radius[key]
            if r is None:
                self.moving[key] = self.vP[body], self.aP[body]
            else:
                v = self.iw[body] * r
                v += self.vP[body]
                acc = self.spin[body] * r
                acc += self.aP[body]
                self.moving[key] = v, acc
        return self.moving[key]

    def run(self, x: np.ndarray, signs: list[np.ndarray | float], tol: float) -> None:
        dyad = 0
        for op in self.prog.ops:
            if isinstance(op, CrankOp):
                self.crank(op, x[op.index, self.sl])
            else:
                sign = signs[op.step]
                self.rrr(op, dyad, sign[self.sl] if isinstance(sign, np.ndarray) else sign, tol)
                dyad += 1
        out, sl = self.out, self.sl
        for name, holder, _ in self.prog.points:
            if holder is None:
                continue
            xw = self.point(holder, name)
            dest = out.points[name][sl]
            if not np.shares_memory(xw, dest):
                dest[...] = xw
            if self.derivatives:
                v, acc = self.rates_of(holder, name)
                out.velocities[name][sl] = v
                out.accelerations[name][sl] = acc
                if not self.finite:
                    unbounded(out.velocities[name][sl])
                    unbounded(out.accelerations[name][sl])
        if self.derivatives and self.extras and not self.finite:
            for body in self.prog.frames:
                unbounded(out.omegas[body][sl])
                unbounded(out.alphas[body][sl])

    def crank(self, op: CrankOp, values: np.ndarray) -> None:
        """The crank turned by ``values`` - drawn (rad): its rotation by the tangent half-angle (cos and sin to
        about 1e-16 from one vectorised tangent: numpy's float64 cosine and sine are not vectorised)."""
        if self.derivatives and not np.isfinite(values).all():
            self.finite = False
        h = np.subtract(values, op.drawn)
        h *= 0.5
        np.tan(h, out=h)
        h2 = np.square(h)
        inv = h2 + 1.0
        np.reciprocal(inv, out=inv)
        e = np.empty(self.m, dtype=complex)
        np.subtract(1.0, h2, out=e.real)
        e.real *= inv
        np.multiply(h, inv, out=e.imag)
        e.imag *= 2.0
        pw = self.point(None, op.pivot)
        self.P[op.body] = pw
        self.a[op.body] = e
        self.place(op.body, op.pivot, pw, None)
        if self.extras:
            np.multiply(e, self.prog.frames[op.body].f, out=self.out.rotations[op.body][self.sl])
        if not self.derivatives:
            return
        # about a ground pivot at constant speed: its velocity and acceleration factors i w and -w^2 are numbers
        rate = float(self.rates[op.index])
        self.vP[op.body], self.aP[op.body] = 0j, 0j
        self.iw[op.body], self.spin[op.body] = 1j * rate, -rate * rate + 0j
        if self.extras:
            self.out.omegas[op.body][self.sl] = rate
            self.out.alphas[op.body][self.sl] = 0.0

    def rrr(self, op: RRROp, dyad: int, sign: np.ndarray | float, tol: float) -> None:
        """Place an RRR dyad: its joint J = p1 + d (along + i height) from the pins' frame (d = p2 - p1), each
        body's vector from its pin to J; its margin into ``ok``; with derivatives the 2x2 closure solved in
        closed form, i w1 a - i w2 b = v2 - v1 (a, b the vectors from the pins to J)."""
        out, sl, m = self.out, self.sl, self.m
        p1, p2 = self.point(op.refs[0], op.pins[0]), self.point(op.refs[1], op.pins[1])
        d = np.subtract(p2, p1)        # an array: a dyad has a moving pin
        dd = np.square(d.real)
        dd += np.square(d.imag)
        # one reduction (NaN poses ignored: they stay NaN) answers both: do the pins meet, may dd divide?
        near = float(np.fmin.reduce(dd))
        if op.deltoid and near <= op.fold_reach**2:
            raise Folded
        prod = op.area_squared(dd)
        # one reduction (NaN kept: not >= anything) spares the clamp and the margin's test where all is in reach
        low = float(prod.min())
        inv = np.divide(0.5, dd if near > 0.0 else np.where(dd > 0, dd, 1.0))
        wj = np.empty(m, dtype=complex)
        np.multiply(inv, op.r1 * op.r1 - op.r2 * op.r2, out=wj.real)
        wj.real += 0.5                 # along: (dd + r1^2 - r2^2) / (2 dd)
        if not low >= 0.0:
            np.maximum(prod, 0.0, out=wj.imag)
            np.sqrt(wj.imag, out=wj.imag)
        else:
            np.sqrt(prod, out=wj.imag)
        wj.imag *= inv                 # height: 4 area / (2 dd), on the branch's side
        if isinstance(sign, np.ndarray) or sign < 0:
            wj.imag *= sign
        a = np.multiply(d, wj, out=wj)  # pin 1 -> J
        dest = self.dest(op.bodies[0], op.joint)
        jw = np.add(p1, a, out=self.dest(op.bodies[1], op.joint) if dest is None else dest)
        b1, b2 = op.bodies
        self.P[b1], self.a[b1] = p1, a
        self.place(b1, op.pins[0], p1, None)
        self.place(b1, op.joint, jw, a)
        self.P[b2] = p2
        self.place(b2, op.pins[1], p2, None)
        self.later[b2] = (jw, p2)      # pin 2 -> J, b = J - p2, made only where it is asked for
        floor = -(tol * 2.0 * op.r1 * op.r2) ** 2
        if not low >= floor:
            out.ok[sl] &= prod >= floor                # the margin 4 area / (2 r1 r2) >= -tol
        b = self.vector(b2) if self.extras or self.derivatives else None
        self.place(b2, op.joint, jw, b)
        if self.extras and b is not None:
            a4 = np.copysign(np.sqrt(np.abs(prod)), prod)
            dist = np.sqrt(dd)
            np.multiply(a, self.prog.frames[b1].f, out=out.rotations[b1][sl])
            np.multiply(b, self.prog.frames[b2].f, out=out.rotations[b2][sl])
            np.divide(a4, 2.0 * op.r1 * op.r2, out=out.margins[dyad][sl])
            ab = np.conjugate(a)
            ab *= b                    # dot(a, b) + i cross(a, b)
            np.arctan2(np.abs(ab.imag), ab.real, out=out.transmissions[dyad][sl])
            slack = np.minimum(op.r1 + op.r2 - dist, dist - abs(op.r1 - op.r2))
            mag = _magnitude(p1, p2, m)
            mag += op.r1 + op.r2
            np.divide(slack, mag, out=out.slacks[dyad][sl])
        if self.derivatives and b is not None:
            self.rrr_rates(op, dyad, d, a, b)

    def rrr_rates(self, op: RRROp, dyad: int, d: np.ndarray, a: np.ndarray, b: np.ndarray) -> None:
        """The dyad's angular velocities and accelerations: i w1 a - i w2 b = v2 - v1 gives w1 = -(dv . b) / (a x b)
        and w2 = -(dv . a) / (a x b) (a x b = Im(a conj b)); the same with the accelerations' right-hand side."""
        out, sl = self.out, self.sl
        (b1, b2), (k1, k2) = op.bodies, op.refs
        v1, c1 = self.rates_of(k1, op.pins[0])
        v2, c2 = self.rates_of(k2, op.pins[1])
        dv = v2 - v1
        den = a.imag * b.real
        den -= a.real * b.imag
        if not (den.all() and np.isfinite(den).all()):
            self.finite = False
        w1, w2 = _dot(dv, b), _dot(dv, a)
        _over(w1, den)
        _over(w2, den)
        da = c2 - c1
        da -= np.square(w2) * b
        da += np.square(w1) * a
        al1, al2 = _dot(da, b), _dot(da, a)
        _over(al1, den)
        _over(al2, den)
        for body, w, al, v, c in ((b1, w1, al1, v1, c1), (b2, w2, al2, v2, c2)):
            self.vP[body], self.aP[body] = v, c
            iw = np.empty(len(w), dtype=complex)
            iw.real.fill(0.0)
            iw.imag[:] = w
            self.iw[body] = iw
            self.spin[body] = _spin(w, al)
            if self.extras:
                out.omegas[body][sl] = w
                out.alphas[body][sl] = al
        if self.extras:
            np.copyto(out.spreads[dyad][sl], _dot(d, np.asarray(dv)))


def _dot(u: np.ndarray | complex, v: np.ndarray) -> np.ndarray:
    """The dot product of complex numbers as plane vectors: Re(u conj v)."""
    out = np.multiply(np.real(u), v.real)
    out += np.imag(u) * v.imag
    return out


def _over(num: np.ndarray, den: np.ndarray) -> None:
    """num <- -num / den in place; +-inf where den is 0 (0 where both are): a toggle, never NaN (the general
    solve's rule for its 2x2 solve)."""
    np.negative(num, out=num)
    if den.all():
        num /= den
    else:
        num[...] = _ratio(num, den)


def _spin(w: np.ndarray, al: np.ndarray) -> np.ndarray:
    """The complex factor -w^2 + i al that takes a radius vector r to its acceleration about the body's point."""
    k = np.empty(len(w), dtype=complex)
    np.square(w, out=k.real)
    np.negative(k.real, out=k.real)
    k.imag[:] = al
    return k


def _ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den; +-inf where den is 0 (0 where both are): a toggle, never NaN (the general solve's rule)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num / den
    if not den.all():
        bad = den == 0
        out[bad] = np.where(num[bad] == 0, 0.0, np.copysign(np.inf, num[bad]))
    return out


def _magnitude(p1: np.ndarray | complex, p2: np.ndarray | complex, m: int) -> np.ndarray:
    """The largest coordinate magnitude (mm) of two points at each pose."""
    out = np.zeros(m)
    for p in (p1, p2):
        for part in (p.real, p.imag):
            np.maximum(out, np.abs(part), out=out)
    return out


def point_view(z: np.ndarray) -> np.ndarray:
    """A complex (n,) array as the (n, 2) float array of its real and imaginary parts (a view: no copy)."""
    return z.view(np.float64).reshape(len(z), 2)


def constant_point(xd: complex, n: int) -> np.ndarray:
    """A ground point over n poses: one (2,) row broadcast (read-only, no memory per pose)."""
    row = np.array([xd.real, xd.imag])
    row.flags.writeable = False        # a view with stride 0 over the poses: as np.broadcast_to's, at a tenth the cost
    return np.ndarray((n, 2), dtype=np.float64, buffer=row, strides=(0, row.itemsize))


def unbounded(z: np.ndarray) -> np.ndarray:
    """Rates past a toggle are +inf, never NaN (in place, as the general solve's rule)."""
    view = z.view(np.float64) if np.iscomplexobj(z) else z
    np.copyto(view, np.inf, where=np.isnan(view))
    return z
