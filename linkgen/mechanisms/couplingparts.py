"""The parts of the course's couplings and double sliders (:mod:`linkgen.mechanisms.couplings`), in the kinematics'
frames (:mod:`linkgen.kinematics.couplings`), with their motion; the layers are found by
:func:`linkgen.parts.layer_order`.

A prismatic pair is cut as everywhere in linkgen: a pin of one part running in a slot of the other.

* **Oldham**: two hub discs and the middle disc. The middle disc carries four pins, two on hub 1's slot line and two
  on hub 2's, ``k`` = offset + hole + width / 2 from its centre (its centre hole marks C); each hub has two slots
  along its diameter over the pins' travel (2 offsets), clear of its bore. Shaft 2 comes from the other side (a top
  plate), as in a coupling between two shafts.
* **Trammel**: the base plate with two guide slots, one parallel to each axis and offset ``g`` from it (so that they
  never cross); each block a bar from its rod pin (on its axis) to its guide pin (in its slot); the rod with its
  pins A and B and the tracer's pen hole P. The guides' offset g clears the rod, the blocks and the tracer.
* **Rapson**: the base plate with the rudder stock's hole and the crosshead's slot; the crosshead (a block whose pin
  runs in that slot and in the tiller's slot: the swivel); the tiller with its slot over the block's travel.
"""
from __future__ import annotations

import math

import numpy as np

from linkgen.kinematics.couplings import Oldham, Rapson, Trammel
from linkgen.parts import SWEEP, Layout, LinkPart, Placement, Stock


def _rows(v: np.ndarray, n: int) -> np.ndarray:
    return np.broadcast_to(np.asarray(v, dtype=float), (n, 2)).copy()


def _turned(v: tuple[float, float], angle: np.ndarray) -> np.ndarray:
    """The local vector ``v`` turned by ``angle`` (rad), (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def oldham_pin_radius(offset: float, stock: Stock, width: float) -> float:
    """The middle disc's pins' distance from its centre (mm): clear of the hubs' bores by half the parts' width."""
    return offset + stock.hole + width / 2


def _oldham_placement(o: Oldham, theta: np.ndarray, k: float) -> Placement:
    m = o.motion(theta, 1.0)
    n = len(theta)
    zero = np.zeros(n)
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {
        "O1": (("ground", "hub1"), np.zeros((n, 2))), "O2": (("ground", "hub2"), _rows(np.array([o.offset, 0.0]), n))}
    for name, hub, local in (("P1", "hub1", (k, 0.0)), ("P2", "hub1", (-k, 0.0)), ("P3", "hub2", (0.0, k)),
                             ("P4", "hub2", (0.0, -k))):
        joints[name] = (("disc", hub), m.centre + _turned(local, m.disc))
    return Placement({"ground": zero, "hub1": m.theta, "hub2": m.output, "disc": m.disc},
                     {"ground": np.zeros((n, 2)), "hub1": np.zeros((n, 2)),
                      "hub2": _rows(np.array([o.offset, 0.0]), n), "disc": m.centre}, joints)


def oldham_layout(o: Oldham, stock: Stock, width: float) -> Layout:
    """Base plate, the two hubs and the middle disc over a turn; drawn at the input angle 0 (C at O2) and 45
    degrees (C on top of its circle)."""
    d, h, w = o.offset, stock.hole, width
    k = oldham_pin_radius(d, stock, w)
    half = w / 2
    hub_radius = k + d + h / 2 + half
    slot = ((np.array([k - d, 0.0]), np.array([k + d, 0.0])), (np.array([-k - d, 0.0]), np.array([-k + d, 0.0])))
    # hub 2's slot runs along its local +Y (square to hub 1's): its frame turns with the input
    slot2 = tuple((a[::-1].copy(), b[::-1].copy()) for a, b in slot)
    centre = np.zeros((1, 2))
    parts = (LinkPart("ground", np.array([[0.0, 0.0], [d, 0.0]]), half, stock, moving=False),
             LinkPart("hub1", centre, hub_radius, stock, slots=slot, body=centre),
             LinkPart("hub2", centre, hub_radius, stock, slots=slot2, body=centre),
             LinkPart("disc", np.array([[0.0, 0.0], [k, 0.0], [-k, 0.0], [0.0, k], [0.0, -k]]), k + h / 2 + half,
                      stock, body=centre))
    sweep = _oldham_placement(o, np.linspace(0.0, 2 * math.pi, SWEEP), k)
    positions = (("drawn", 0.0), ("quarter", math.pi / 4))
    poses = tuple(_oldham_placement(o, np.array([t]), k) for _, t in positions)
    return Layout(parts, sweep, positions, poses, (sweep.origins["disc"],))


def trammel_guide_offset(t: Trammel, stock: Stock, width: float) -> float:
    """How far each guide slot lies from its axis (mm): beyond every point of the rod and the tracer, by a hole and
    the parts' width."""
    return max(t.rod, *t.semi_axes) + stock.hole + width


def _trammel_placement(t: Trammel, phi: np.ndarray, g: float) -> Placement:
    m = t.motion(phi, 1.0)
    n = len(phi)
    a = np.column_stack([m.a, np.zeros(n)])
    b = np.column_stack([np.zeros(n), m.b])
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {
        "A": (("block-a", "rod"), a), "B": (("block-b", "rod"), b),
        "block-a-slot": (("block-a", "ground"), a + np.array([0.0, -g])),
        "block-b-slot": (("block-b", "ground"), b + np.array([-g, 0.0]))}
    return Placement({"ground": np.zeros(n), "block-a": np.full(n, -math.pi / 2), "block-b": np.full(n, math.pi),
                      "rod": m.rod_angle}, {"ground": np.zeros((n, 2)), "block-a": a, "block-b": b, "rod": a}, joints)


def trammel_layout(t: Trammel, stock: Stock, width: float) -> Layout:
    """Base plate with the two guide slots, the blocks and the rod over a turn of the rod; drawn at phi = 0 and 90
    degrees (each block at a dead centre of its guide)."""
    g = trammel_guide_offset(t, stock, width)
    half = width / 2
    slots = ((np.array([-t.rod, -g]), np.array([t.rod, -g])), (np.array([-g, -t.rod]), np.array([-g, t.rod])))
    ends = np.array([p for slot in slots for p in slot])
    holes = [[0.0, 0.0], [t.rod, 0.0]] + ([[t.point, 0.0]] if t.point not in (0.0, t.rod) else [])
    bar = np.array([[0.0, 0.0], [g, 0.0]])
    parts = (LinkPart("ground", np.zeros((0, 2)), half, stock, slots=slots, moving=False, body=ends),
             LinkPart("block-a", bar, half, stock), LinkPart("block-b", bar, half, stock),
             LinkPart("rod", np.array(holes), half, stock))
    sweep = _trammel_placement(t, np.linspace(0.0, 2 * math.pi, SWEEP), g)
    positions = (("a-end", 0.0), ("b-end", math.pi / 2))
    poses = tuple(_trammel_placement(t, np.array([p]), g) for _, p in positions)
    point = t.motion(np.linspace(0.0, 2 * math.pi, SWEEP), 1.0).point
    return Layout(parts, sweep, positions, poses, (point,))


def _rapson_placement(r: Rapson, y: np.ndarray) -> Placement:
    m = r.motion(y, 1.0)
    n = len(y)
    pin = np.column_stack([np.full(n, r.distance), y])
    return Placement({"ground": np.zeros(n), "crosshead": np.full(n, math.pi / 2), "tiller": m.angle},
                     {"ground": np.zeros((n, 2)), "crosshead": pin, "tiller": np.zeros((n, 2))},
                     {"stock": (("ground", "tiller"), np.zeros((n, 2))),
                      "crosshead-slot": (("crosshead", "ground"), pin), "swivel": (("crosshead", "tiller"), pin)})


def rapson_layout(r: Rapson, max_angle: float, stock: Stock, width: float) -> Layout:
    """Base plate, crosshead and tiller over the crosshead's travel (helm from -max_angle to max_angle, rad); drawn
    at both ends of the travel and amidships."""
    travel = r.travel(max_angle)
    half = width / 2
    far = r.distance / math.cos(max_angle)
    slot = (np.array([r.distance, -travel]), np.array([r.distance, travel]))
    tiller_slot = (np.array([r.distance, 0.0]), np.array([far, 0.0]))
    parts = (LinkPart("ground", np.zeros((1, 2)), half, stock, slots=(slot,), moving=False,
                      body=np.array([[0.0, 0.0], *slot])),
             LinkPart("crosshead", np.zeros((1, 2)), half, stock, body=np.array([[-width, 0.0], [width, 0.0]])),
             LinkPart("tiller", np.zeros((1, 2)), half, stock, slots=(tiller_slot,),
                      body=np.array([[0.0, 0.0], [far + stock.hole, 0.0]])))
    sweep = _rapson_placement(r, np.linspace(-travel, travel, SWEEP))
    positions = (("hard-over-starboard", -travel), ("amidships", 0.0), ("hard-over-port", travel))
    poses = tuple(_rapson_placement(r, np.array([y])) for _, y in positions)
    return Layout(parts, sweep, positions, poses, (sweep.origins["crosshead"],))
