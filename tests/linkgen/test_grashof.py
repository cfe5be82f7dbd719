"""Grashof class and inversion names for every choice of ground and input, change points and degenerate chains."""
from __future__ import annotations

import itertools

import pytest

from camgen.core.errors import SpecError
from linkgen.kinematics.grashof import classify, classify_chain

# A Grashof chain in loop order with the shortest link at index 0 (2 + 6 < 4 + 5).
CHAIN = (2.0, 5.0, 6.0, 4.0)


@pytest.mark.parametrize("ground, driven", [(g, (g + s) % 4) for g in range(4) for s in (1, 3)])
def test_every_inversion_of_a_grashof_chain(ground, driven):
    """Grashof's law (Norton, Design of Machinery, sec. 2.12): the shortest link S decides the inversion."""
    g = classify_chain(CHAIN, ground, driven)
    output, coupler = (2 * ground - driven) % 4, (ground + 2) % 4     # the ground's other neighbour, its opposite
    shortest = 0
    expected = {ground: "double-crank", driven: "crank-rocker", output: "rocker-crank",
                coupler: "double-rocker"}[shortest]
    assert g.grashof_class == "I"
    assert g.inversion == expected
    assert g.margin == pytest.approx(1.0)


def test_named_examples():
    assert classify(180, 80, 200, 150).inversion == "crank-rocker"          # the template
    assert classify(180, 150, 200, 80).inversion == "rocker-crank"
    assert classify(50, 150, 200, 180).inversion == "double-crank"           # drag link: ground shortest
    assert classify(180, 150, 50, 200).inversion == "double-rocker"          # coupler shortest
    t = classify(100, 70, 60, 80)                                            # 60 + 100 > 70 + 80
    assert (t.grashof_class, t.inversion, t.margin) == ("II", "triple-rocker", pytest.approx(-10.0))


@pytest.mark.parametrize("lengths, form, name", [
    ((4.0, 2.0, 4.0, 2.0), "parallelogram", "change-point double-crank"),
    ((2.0, 4.0, 2.0, 4.0), "parallelogram", "change-point double-crank"),
    ((4.0, 4.0, 2.0, 2.0), "deltoid", "change-point rocker-crank"),
    ((2.0, 2.0, 4.0, 4.0), "deltoid", "change-point double-crank"),
    ((3.0, 3.0, 3.0, 3.0), "rhombus", "change-point double-crank"),
    ((3.0, 2.0, 5.0, 4.0), None, "change-point crank-rocker"),               # 2 + 5 = 3 + 4
])
def test_change_points_and_their_forms(lengths, form, name):
    g = classify(*lengths)
    assert (g.grashof_class, g.form, g.inversion) == ("III", form, name)


@pytest.mark.parametrize("nudge, cls", [(0.0, "III"), (1e-12, "III"), (-1e-12, "III"), (1e-8, "II"), (-1e-8, "I")])
def test_near_change_points(nudge, cls):
    """S + L = P + Q is a change point within 1e-10 of the longest link: 1e-12 away it is, 1e-8 away not."""
    longest = 5.0 + nudge                # grows S + L by nudge (mm)
    assert classify(2.0, 3.0, longest, 4.0).grashof_class == cls


@pytest.mark.parametrize("lengths, field", [
    ((0.0, 2.0, 3.0, 4.0), "linkage.ground"),
    ((1.0, -2.0, 3.0, 4.0), "linkage.crank"),
    ((1.0, 2.0, 3.0, 6.0), "linkage.rocker"),            # 6 = 1 + 2 + 3: only flat
    ((1.0, 2.0, 30.0, 4.0), "linkage.coupler"),
])
def test_degenerate_lengths_are_refused(lengths, field):
    from linkgen.kinematics.fourbar import FourBar

    with pytest.raises(SpecError) as err:
        FourBar(*lengths)
    assert str(err.value).startswith(field)


def test_input_must_be_next_to_the_ground():
    with pytest.raises(SpecError, match="next to the ground"):
        classify_chain(CHAIN, 0, 2)


def test_names_cover_all_permutations_consistently():
    """Swapping input and output swaps crank-rocker and rocker-crank, for every ordering of the lengths."""
    swap = {"crank-rocker": "rocker-crank", "rocker-crank": "crank-rocker"}
    for g, i, c, o in itertools.permutations(CHAIN):
        a, b = classify(g, i, c, o), classify(g, o, c, i)
        assert b.inversion == swap.get(a.inversion, a.inversion)
