"""Higher pairs in the solve: a gear pair or a rack and pinion places one body from its partner, in closed form.

A gear step (:class:`~linkgen.kinematics.structure.GearStep`) places a body that turns about its gear's centre on a
known body, or a rack that slides along its slider's known guide, from the turn of its partner. Turns are from the
drawing, rad, counter-clockwise; travels mm along the guide from the drawing.

**Gear pair** (Willis): with phi_L the turn of the line of centres (the carrier's, the body that holds both centres,
or the line's own where none does), ``phi_1 - phi_L = k (phi_0 - phi_L)``, k = -z0 / z1 external, +z0 / z1 internal
(:class:`~linkgen.kinematics.structure.Gear`). Differentiated at unit input speed: ``w_1 = w_L + k (w_0 - w_L)``,
``al_1 = al_L + k (al_0 - al_L)``; without a carrier ``w_L = (d x d') / |d|^2`` and
``al_L = (d x d'') / |d|^2 - 2 w_L (d . d') / |d|^2`` for d the vector between the centres.

**Rack and pinion**: the rack's travel relative to its guide t = lead psi, psi the pinion's turn relative to the guide
(:class:`~linkgen.kinematics.structure.Rack`), so ``t' = lead (w_p - w_g)`` and ``t'' = lead (al_p - al_g)``; from
the rack the other way, psi = t / lead with t, t', t'' the rack's relative travel and its rates along the guide.

Turns: a turn known exactly (the ground's, an input's, one a gear step gave from exact turns) is carried as it is,
beyond a half turn; the turn of a body placed by a dyad is read from its rotation, in (-pi, pi] from the drawing (a
rocker swinging less than half a turn either way of its drawing, or any link where the ratio is whole).
"""
from __future__ import annotations

import numpy as np

from linkgen.kinematics.dyads import cross, dot
from linkgen.kinematics.linkage import Body, Motion, _direction, _pinned, _pt, pivoted, slid
from linkgen.kinematics.structure import Gear, GearStep, Pin, Rack, Structure


def turn_of(bodies: dict[str, Body], turns: dict[str, np.ndarray], name: str) -> np.ndarray:
    """A placed body's turn from the drawing (rad): exact where known, else its rotation's angle in (-pi, pi]."""
    if name in turns:
        return turns[name]
    body = bodies[name]
    return np.arctan2(body.s, body.c)


def place(s: Structure, step: GearStep, bodies: dict[str, Body], motions: dict[str, Motion] | None,
          turns: dict[str, np.ndarray]) -> None:
    """Place the body of a gear step (its motion too, given ``motions``) and its turn where it is exact."""
    pair = next(p for p in s.pairs if p.name == step.pair)
    if isinstance(pair, Gear):
        _place_gear(s, step, pair, bodies, motions, turns)
    else:
        _place_rack(s, step, pair, bodies, motions, turns)


def _place_gear(s: Structure, step: GearStep, gear: Gear, bodies: dict[str, Body],
                motions: dict[str, Motion] | None, turns: dict[str, np.ndarray]) -> None:
    pin = step.attachment
    assert isinstance(pin, Pin)
    placed = gear.bodies.index(step.body)
    ratio = gear.ratio if placed == 1 else 1.0 / gear.ratio
    cd, pd = _pt(s, pin.point), _pt(s, gear.centres[1 - placed])
    cw, pw = bodies[pin.body].at(cd), bodies[step.partner].at(pd)
    carrier = s.carrier(gear)
    d = cw - pw
    if carrier is not None and carrier in bodies:
        line = turn_of(bodies, turns, carrier)
        exact = carrier in turns
    else:
        drawn = cd - pd
        line = np.arctan2(cross(drawn, d), dot(drawn, d))
        exact = False
    phi = line + ratio * (turn_of(bodies, turns, step.partner) - line)
    body = _pinned(np.cos(phi), np.sin(phi), cw, cd)
    bodies[step.body] = body
    if exact and step.partner in turns:
        turns[step.body] = phi
    if motions is None:
        return
    holder, partner = motions[pin.body], motions[step.partner]
    if carrier is not None and carrier in motions:
        w_line, al_line = motions[carrier].w, motions[carrier].al
    else:
        dv, da = holder.vel(cw) - partner.vel(pw), holder.acc(cw) - partner.acc(pw)
        dd = dot(d, d)
        w_line = cross(d, dv) / dd
        al_line = cross(d, da) / dd - 2.0 * w_line * dot(d, dv) / dd
    w = w_line + ratio * (partner.w - w_line)
    al = al_line + ratio * (partner.al - al_line)
    motions[step.body] = pivoted(holder, cw, body.T, w, al)


def _place_rack(s: Structure, step: GearStep, rack: Rack, bodies: dict[str, Body],
                motions: dict[str, Motion] | None, turns: dict[str, np.ndarray]) -> None:
    sl = s.slider_by_name[rack.slider]
    guide = bodies[sl.guide]
    u = guide.rotate(_direction(sl.angle))
    if step.body == sl.body:                       # the rack, from its pinion's turn
        psi = turn_of(bodies, turns, rack.pinion) - turn_of(bodies, turns, sl.guide)
        t = rack.lead * psi
        body = Body(guide.c, guide.s, guide.T + t[:, None] * u)
        bodies[step.body] = body
        if sl.guide in turns:
            turns[step.body] = turns[sl.guide]
        if motions is not None:
            g, p = motions[sl.guide], motions[rack.pinion]
            motions[step.body] = slid(g, body.T, u, t, rack.lead * (p.w - g.w), rack.lead * (p.al - g.al))
        return
    t = dot(bodies[sl.body].T - guide.T, u)        # the pinion, from its rack's travel
    cd = _pt(s, rack.centre)
    cw = guide.at(cd)
    phi = turn_of(bodies, turns, sl.guide) + t / rack.lead
    body = _pinned(np.cos(phi), np.sin(phi), cw, cd)
    bodies[step.body] = body
    if sl.guide in turns:
        turns[step.body] = phi
    if motions is not None:
        g, r = motions[sl.guide], motions[sl.body]
        tdot, tddot = dot(u, r.vel(cw) - g.vel(cw)), dot(u, r.acc(cw) - g.acc(cw))
        motions[step.body] = pivoted(g, cw, body.T, g.w + tdot / rack.lead, g.al + tddot / rack.lead)
