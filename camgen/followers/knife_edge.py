"""The knife-edge follower: a translating roller of radius 0 (see :mod:`camgen.followers.translating_roller`)."""
from __future__ import annotations

import math

from camgen.followers.base import FollowerType
from camgen.followers.translating_roller import TranslatingRoller

FOLLOWER = FollowerType(
    "knife-edge", make=lambda t, rb, rr, sense: TranslatingRoller(rb + rr, rr, t.offset, sense),
    base_radius_range=lambda t, rr, top: (max(0.0, abs(t.offset) - rr), math.inf))
