"""A conjugate pair whose second roller has its own radius (cam.second_roller_radius): both rollers touch their
cams read back from the DXFs over the whole turn, the second roller placed by closed forms; cam 2's base circle
kept; an undercut of cam 2 names the key; other kinds refuse it."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.spec import validate_spec
from tests.support.refusals import assert_refused
from tests.camgen.kinds.conjugate.test_conjugate import ARM, YOKE, _build, _layer, _raw, _rollers, _turn

R2 = 5.0                                              # the second roller's radius (the first's is 8 mm)


def _place(raw: dict) -> dict:
    """The second roller's place by closed forms for equal base circles Rb, the second roller's prime radius
    Rb + R2 reached at the largest lift h: a yoke's span sqrt(Rp1^2 - e^2) + h + sqrt(Rp2^2 - e^2); a bell crank's
    arm angle psi0 + psi_max + alpha, Rp2^2 = C^2 + L^2 - 2 C L cos(alpha)."""
    f, rb = raw["follower"], raw["cam"]["base_radius"]
    rp1, rp2 = rb + f["roller_radius"], rb + R2
    lift = max(seg.get("lift", 0.0) for seg in raw["motion"])
    if f["type"] == "translating-roller":
        return {"span": math.sqrt(rp1 ** 2) + lift + rp2}
    c, arm = f["pivot_distance"], f["arm_length"]
    psi0 = math.acos((c * c + arm * arm - rp1 * rp1) / (2 * c * arm))
    alpha = math.acos((c * c + arm * arm - rp2 * rp2) / (2 * c * arm))
    return {"angle": psi0 + math.radians(lift) + alpha, "length": arm}


@pytest.mark.parametrize("template, rotation", [(YOKE, "ccw"), (YOKE, "cw"), (ARM, "ccw"), (ARM, "cw")])
def test_both_rollers_of_their_own_sizes_touch_their_cams(template, rotation, tmp_path):
    """Both rollers at 720 cam angles, placed from the template's numbers and closed forms, each against its cam's
    outline read back from its DXF: the gap less its own radius within the tolerance, never inside the cam; cam 2's
    profile comes as near the shaft as its base circle, Rb (its pitch curve R2 further out)."""
    import shapely

    raw = _raw(template, None, rotation=rotation)
    raw["cam"]["second_roller_radius"] = R2
    report, out = _build(tmp_path, template, "output.formats=['dxf','json']", f"cam.second_roller_radius={R2}",
                         f'cam.rotation="{rotation}"')
    assert report["follower"]["second_roller"]["roller_radius_mm"] == R2
    tol = report["tolerance_mm"]
    theta = np.radians(np.arange(720) / 2)
    design = design_cam(validate_spec(raw))
    s = design.cam.program.evaluate(theta)[0]
    sense = 1 if rotation == "ccw" else -1
    for which, (centre, rr) in enumerate(zip(_rollers(raw, s, _place(raw)), (8.0, R2), strict=True)):
        (ring,) = _layer(out / f"{template.stem}-{which + 1}.dxf", "OUTLINE")
        body = shapely.Polygon(ring)
        at = _turn(centre, -sense * theta)
        gap = shapely.distance(body.exterior, shapely.points(at)) - rr
        assert not shapely.contains_xy(body, at[:, 0], at[:, 1]).any()
        assert np.abs(gap).max() <= tol, (which, gap.min(), gap.max())
    (ring,) = _layer(out / f"{template.stem}-2.dxf", "OUTLINE")
    assert np.linalg.norm(ring, axis=1).min() == pytest.approx(40.0, abs=tol)
    assert design.second.contact_radius == R2 and design.cam.contact_radius == 8.0


def test_an_undercut_of_cam_2_names_its_roller_and_the_largest_that_fits():
    """A 30 mm second roller on a 5 mm second base circle undercuts cam 2; the message names
    cam.second_roller_radius and the largest that fits, which builds, while 1e-6 more undercuts."""
    import re

    raw = _raw(YOKE, None, second_base_radius=5.0, bore=0.0)
    raw["cam"]["second_roller_radius"] = 30.0
    raw["hub"] = {**raw.get("hub", {}), "keyway": False}
    with pytest.raises(DesignError, match=r"undercut of cam 2 .* smaller than cam.second_roller_radius 30 mm; the "
                                          r"largest second roller that fits cam 2 is") as caught:
        design_cam(validate_spec(raw))
    best = float(re.search(r"fits cam 2 is ([0-9.]+) mm", str(caught.value)).group(1))
    from camgen.kinds.conjugate.design import Placement, largest_second_roller, pair_rig

    spec = validate_spec(raw)
    exact = largest_second_roller(pair_rig(spec), spec.cam.base_radius, Placement.of(spec.cam), 5.0)
    assert exact == pytest.approx(best, rel=1e-3)
    raw["cam"]["second_roller_radius"] = exact
    design = design_cam(validate_spec(raw))
    assert design.cams[1].analysis.pitch_rho_min_mm - exact == pytest.approx(0.0, abs=1e-6)
    raw["cam"]["second_roller_radius"] = exact * (1 + 1e-6)
    with pytest.raises(DesignError, match="undercut of cam 2"):
        design_cam(validate_spec(raw))


def test_without_it_the_second_roller_is_the_first(tmp_path):
    plain = design_cam(validate_spec(_raw(YOKE)))
    assert plain.second.contact_radius == plain.cam.contact_radius == 8.0
    assert plain.second.follower.radius is None


@pytest.mark.parametrize("change, message", [
    ({"cam.second_roller_radius": 0.0}, "cam.second_roller_radius: must be > 0"),
    ({"cam.second_roller_radius": -2.0}, "cam.second_roller_radius: must be > 0"),
])
def test_bad_second_radii_are_refused(change, message, tmp_path):
    assert_refused(YOKE, change, message, tmp_path)


def test_other_kinds_refuse_it(tmp_path):
    from tests.conftest import ROOT

    assert_refused(ROOT / "templates" / "rdrd.toml", {"cam.second_roller_radius": 5.0},
                   'cam.second_roller_radius: not a key of a disc cam (a key of cam.kind = "conjugate"); it takes: ',
                   tmp_path)
