"""The composition of a machine's motion, pure numpy: a cam's program on a phased shaft, its follower's swing as a
four-bar's crank angle (the chain rule through the coupling), the output's rates, the timing diagram's dwells and
overlaps, and the camshaft torque by virtual work.

Angles: the main shaft's angle phi (radians, from the machine's start, in its sense of rotation); a cam's program
angle theta = n phi - phase (its shaft's ``n`` turns per main turn, ``phase`` radians), so the program starts when
the shaft has turned ``phase``; a follower's swing psi in degrees (camgen's unit, positive away from the cam); the
four-bar's crank angle theta2 = rest + psi (radians, counter-clockwise from its ground line). Rates per radian of
the main shaft (multiply by omega, rad/s, for time); torques in N*m, counter-clockwise positive.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

TWO_PI = 2.0 * math.pi
#: a rate at most this fraction of its output's range per radian counts as still (a dwell)
STILL = 1e-9


def shaft_angles(samples: int) -> np.ndarray:
    """``samples`` main shaft angles (radians) evenly over one turn, from 0 (360 degrees left out)."""
    return np.arange(samples) * (TWO_PI / samples)


def program_angles(phi: np.ndarray, turns: float, phase: float) -> np.ndarray:
    """A cam's program angles (radians, in [0, 2 pi)) at main shaft angles ``phi``: its shaft turns ``|turns|``
    times a main turn and its program starts at the shaft's angle ``phase`` (radians)."""
    return np.mod(abs(turns) * phi - phase, TWO_PI)


@dataclass(frozen=True)
class Chain:
    """A follower's swing carried into a four-bar's crank, per radian of the main shaft.

    Attributes
    ----------
    theta2 : ndarray
        The crank angle (radians): rest + psi.
    d1, d2 : ndarray
        d theta2 / d phi (rad/rad) and d^2 theta2 / d phi^2 (rad/rad^2).
    """

    theta2: np.ndarray
    d1: np.ndarray
    d2: np.ndarray


def crank_chain(rest_deg: float, swing: np.ndarray, turns: float) -> Chain:
    """The crank's angle and rates from a follower's ``swing`` (camgen's ``(s, s', s'')`` rows: degrees, degrees
    per radian and per radian^2 of the cam's program) on a shaft of ``turns`` turns per main turn, the crank at
    ``rest_deg`` degrees with the follower at rest."""
    n = abs(turns)
    return follower_chain(rest_deg, np.stack([swing[0], n * swing[1], n * n * swing[2]]))


def follower_chain(rest_deg: float, rows: np.ndarray) -> Chain:
    """The crank's angle and rates from a follower's swing ``rows`` (3, n) already per radian of the main shaft
    (degrees, degrees per radian, per radian^2: on an indexing shaft s' Q' and s'' Q'^2 + s' Q'' by the chain rule
    through its shaft's angle Q), the crank at ``rest_deg`` degrees with the follower at rest."""
    return Chain(np.radians(rest_deg + rows[0]), np.radians(rows[1]), np.radians(rows[2]))


def output_rates(k1: np.ndarray, k2: np.ndarray, chain: Chain) -> tuple[np.ndarray, np.ndarray]:
    """d theta / d phi and d^2 theta / d phi^2 of a link whose angle's derivatives by the crank's are ``k1``
    (d theta / d theta2) and ``k2`` (d^2 theta / d theta2^2): the chain rule, k1 theta2' and
    k2 theta2'^2 + k1 theta2''."""
    return k1 * chain.d1, k2 * chain.d1 ** 2 + k1 * chain.d2


def point_rate(crank: float, distance: float, angle: float, theta3: np.ndarray, k3: np.ndarray,
               chain: Chain) -> np.ndarray:
    """(n, 2) d P / d phi (mm/rad) of the coupler point P = A + distance (cos, sin)(theta3 + angle), the crank pin
    A = crank (cos, sin) theta2, its coupler's angle theta3 changing by ``k3`` = d theta3 / d theta2."""
    ax, ay = -crank * np.sin(chain.theta2), crank * np.cos(chain.theta2)
    ux, uy = -distance * np.sin(theta3 + angle), distance * np.cos(theta3 + angle)
    return np.column_stack(((ax + ux * k3) * chain.d1, (ay + uy * k3) * chain.d1))


def reflected_force(output_torque: float, k1: np.ndarray, arm: float) -> np.ndarray:
    """The force (N) an external torque ``output_torque`` (N*m) on the output link presses the follower onto its
    cam with, along the follower's path, the output turning k1 rad per unit of the linkage's input and the follower
    moving ``arm`` mm per unit of it (an arm's length in mm per radian of its swing; 1 for a stem driving a slider by
    its lift): the linkage holds the input with output_torque k1 (virtual work), which moves the follower the way it
    rises (off the cam) where positive."""
    return -output_torque * k1 * 1000.0 / arm


def shaft_torque(output_torque: float, k1: np.ndarray, rate: np.ndarray) -> np.ndarray:
    """The main shaft's torque (N*m) that works against ``output_torque`` (N*m) on the output link, which turns k1
    rad per unit of the linkage's input (a crank's radian, a slider's mm), the input moving ``rate`` units per radian
    of the main shaft (a crank's theta2'): -T k1 rate (its power, T omega_out, over the shaft's speed)."""
    return -output_torque * k1 * rate


def normalised(values: np.ndarray) -> np.ndarray:
    """``values`` mapped onto [0, 1] by their range over the turn (all 0 where they do not change)."""
    low, span = float(values.min()), float(np.ptp(values))
    return np.zeros_like(values) if span == 0 else (values - low) / span


def still(rate: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Where an output stands still: its rate (per radian of the main shaft) at most :data:`STILL` times its
    range over the turn (everywhere for one that does not move), for two samples or more in a row (a rate passing
    through 0 at one sample is a reversal, not a dwell)."""
    span = float(np.ptp(values))
    if span == 0:
        return np.ones(rate.shape, bool)
    mask = np.abs(rate) <= STILL * span
    lone = mask & ~np.roll(mask, 1) & ~np.roll(mask, -1)         # a momentary stop (a reversal), not a dwell
    return mask & ~lone


def intervals(mask: np.ndarray) -> list[tuple[float, float]]:
    """The runs of True in ``mask`` (samples evenly over one turn, cyclic) as (start, end) main shaft angles in
    degrees, end > start (a run across 0 ends above 360; one round the whole turn is (0, 360))."""
    n = len(mask)
    if mask.all():
        return [(0.0, 360.0)]
    if not mask.any():
        return []
    step = 360.0 / n
    first = int(np.argmin(mask))                     # a False sample: runs are whole from here on
    rolled = np.roll(mask, -first)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], rolled.astype(np.int8), [0]))))
    return [((first + a) * step, (first + b - 1) * step) for a, b in zip(edges[::2], edges[1::2], strict=True)]


def overlap(a: np.ndarray, b: np.ndarray) -> list[tuple[float, float]]:
    """Where two outputs both move (masks of moving samples): the runs of ``a & b`` in degrees."""
    return intervals(a & b)


def crank_inputs(drawn: float, phase_deg: float, angle: np.ndarray) -> np.ndarray:
    """A shaft-driven linkage's crank input (radians, counter-clockwise from +X of its drawing): its drawn value
    ``drawn`` (radians) turned ``phase_deg`` degrees ahead, plus its shaft's ``angle`` Q (radians, counter-clockwise,
    0 at the machine's start: ``turns`` x phi on a uniform shaft, negative turns the other way; an indexing shaft's
    from its Geneva drive, :mod:`camgen.kinds.machine.shaft_motion`)."""
    return drawn + math.radians(phase_deg) + np.asarray(angle, dtype=float)
