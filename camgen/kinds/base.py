"""What every cam kind declares (see :mod:`camgen.kinds`)."""
from __future__ import annotations

import importlib
import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class CamKind:
    """How a cam kind enters a design.

    ``followers``: the follower types it drives. ``check(spec)`` raises ``ValueError("field: why")`` for a
    spec this kind cannot take. ``follower(spec, base radius mm, roller radius mm)`` is the follower on it.
    ``design`` (spec -> design) and ``bundle`` (design -> (bundle, report)) are ``"module:function"`` names.
    """

    name: str
    followers: tuple[str, ...]
    check: Callable[[Any], None]
    follower: Callable[[Any, float, float], Any]
    design: str
    bundle: str

    def designer(self) -> Callable[[Any], Any]:
        """The function designing this kind (spec -> design)."""
        return _resolve(self.design)

    def bundler(self) -> Callable[[Any], Any]:
        """The function turning a design of this kind into (bundle, report)."""
        return _resolve(self.bundle)


def _resolve(name: str) -> Callable[[Any], Any]:
    """The function ``"module:function"`` names, looked up each time (a function patched or reloaded in its module is
    the one used); a loaded module is taken from ``sys.modules`` without importlib's machinery."""
    module, _, attr = name.partition(":")
    return getattr(sys.modules.get(module) or importlib.import_module(module), attr)


#: the ``[cam]`` keys only a grooved cam takes
GROOVE_KEYS = ("groove_depth", "running_clearance", "rim")
#: how a message names the grooved kind
GROOVED = 'a grooved cam (cam.kind = "grooved")'
#: the ``[cam]`` keys only a barrel cam takes, and how a message names it
BARREL_KEYS = ("pitch_radius", "length")
BARREL = 'a barrel cam (cam.kind = "barrel")'
#: the ``[cam]`` keys of a barrel's rib (refused for the other kinds)
RIB_KEYS = ("barrel_form", "rib_width")
#: the ``[cam]`` keys only a conjugate cam takes (refused for the other kinds by :class:`camgen.spec.CamTable`)
CONJUGATE_KEYS = ("second_base_radius", "yoke_span", "arm_angle", "second_arm_length", "second_roller_radius")
#: the ``[cam]`` keys every flat cam (disc, plate, grooved, conjugate) needs
FLAT_KEYS = ("base_radius", "thickness")


def flat_body(spec: Any) -> None:
    """The checks every flat cam (disc, plate, grooved, conjugate) shares: ``base_radius`` and ``thickness``
    given (the message pydantic gives a missing key), and no barrel's keys."""
    for key in FLAT_KEYS:
        if getattr(spec.cam, key) is None:
            info = type(spec.cam).model_fields[key]
            raise ValueError(f"cam.{key}: missing: give {info.description} in {info.json_schema_extra['unit']}")
    refuse_keys(spec, (*BARREL_KEYS, *RIB_KEYS), BARREL)
    if "roller_shape" in spec.follower.model_fields_set:
        raise ValueError(f"follower.roller_shape: only for {BARREL}")


def refuse_keys(spec: Any, keys: tuple[str, ...], owner: str) -> None:
    """Raise ``ValueError("cam.<key>: ...")`` for the first of ``keys`` the template gives in ``[cam]``: keys only
    ``owner`` (a kind, described for the message) takes."""
    for key in keys:
        if key in spec.cam.model_fields_set:
            raise ValueError(f"cam.{key}: only for {owner}")
