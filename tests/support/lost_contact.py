"""The spring checks' shared assertions: a follower that a linkage's inertia lifts off its cam, as the cam's own
contact check, its warning and the machine report's ``spring`` entry say it."""
from __future__ import annotations

from typing import Any

import numpy as np
import pytest


def assert_contact_lost(design: Any, cam: str, rows: np.ndarray, spring: dict, phase_deg: float) -> Any:
    """Assert that cams.``cam`` of the machine ``design`` loses contact as ``rows`` (the contact force, N, at each
    whole degree of its program, computed by the test) say: the cam's least force within 2 % of their spread and
    within 2 degrees of where they put it, one warning naming the cam and the angle, and the report's ``spring``
    entry giving the same least force, the preload it needs (more than the one given) and the main shaft's angle
    (its program angle + ``phase_deg``). Returns the cam's contact check."""
    contact = design.cam(cam).design.speed.contact
    assert rows.min() < 0 and contact.holds is False
    assert contact.force_min == pytest.approx(rows.min(), abs=0.02 * np.ptp(rows))
    assert abs((contact.force_min_at_deg - float(np.argmin(rows)) + 180) % 360 - 180) <= 2.0
    lost = [w for w in design.warnings if w.startswith(f"cams.{cam}: the spring loses contact near")]
    assert len(lost) == 1 and f"{contact.force_min_at_deg:.1f} degrees" in lost[0]
    assert spring["holds"] is False and spring["least_contact_force_n"] == pytest.approx(contact.force_min)
    assert spring["preload_needed_n"] == pytest.approx(contact.preload_needed)
    assert contact.preload_needed > contact.preload
    assert spring["at_shaft_deg"] == pytest.approx((spring["at_cam_deg"] + phase_deg) % 360)
    return contact
