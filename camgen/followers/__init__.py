"""Followers: one module a follower type, registered here, the one place a type is looked up.

Every follower gives the cam its pitch curve and contact geometry (see :mod:`camgen.followers.base`
for the frames and sign conventions); its module's ``FOLLOWER`` (a :class:`FollowerType`) says
which template keys it takes and how to build it.
"""
from __future__ import annotations

from typing import Literal

from camgen.followers import knife_edge, oscillating_flat, oscillating_roller, translating_flat, translating_roller
from camgen.followers.base import FollowerType

#: every follower type by its template name, in the order docs/guides/followers.md lists them
FOLLOWERS: dict[str, FollowerType] = {m.FOLLOWER.name: m.FOLLOWER for m in (
    translating_roller, knife_edge, translating_flat, oscillating_roller, oscillating_flat)}
#: the names of :data:`FOLLOWERS`, written out for the type checker (a template's ``follower.type``)
FollowerName = Literal["translating-roller", "knife-edge", "translating-flat", "oscillating-roller",
                       "oscillating-flat"]

__all__ = ["FOLLOWERS", "FollowerName", "FollowerType"]
