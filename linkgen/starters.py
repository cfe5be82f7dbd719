"""Starter templates for ``linkgen new KIND``: one for each mechanism type, with its parts (Whitworth's only
analysed: its parts cannot be stacked), every key commented from the template's models
(:mod:`camgen.core.starter`) and under its ``[linkage]`` heading the rule that type has (:data:`RULES`: what lets its
input turn fully, its proportions), naming only keys that type takes; each analyses and builds as it is."""
from __future__ import annotations

from typing import Any, get_args

from pydantic import BaseModel

from camgen.core.options import choose
from camgen.core.starter import render
from linkgen.mechanisms import MECHANISMS
from linkgen.spec import PartsTable

PARTS = ("parts", {"width": 12.0, "thickness": 4.0, "pin_diameter": 4.0, "clearance": 0.2, "kerf": 0.15,
                   "sheet": [600.0, 400.0], "pins": True})
NOTES = {"linkage.type": "the mechanism; `linkgen new` lists them all",
         "linkage.joints": "each joint's place in the drawing [x, y], mm",
         "linkage.links": "each moving link and the joints it holds (three or more: a plate)"}

#: the rule of each straight-line linkage: its canonical proportions, in units of size (mm)
_STRAIGHT = {
    "chebyshev": "ground 2, crank 2.5, coupler 1, rocker 2.5, crossed; the mid-coupler point runs near-straight for 2",
    "hoekens": "ground 2, crank 1, coupler 2.5, rocker 2.5; the point 5 along the coupler line runs near-straight "
               "for 2",
    "roberts": "pivots 2 apart, rockers and triangle sides 2, triangle base 1; its apex runs near-straight for 2",
    "watt": "rockers 1, coupler 1, pivots 2 across and 1 up, crossed; the mid-coupler point runs near-straight for "
            "0.5"}
#: kind -> comments of its own, as in :data:`camgen.starters.RULES`: under ``[linkage]`` the rule that type has, and
#: for a ``linkage.key`` what that key means for it; they name only keys the type takes (tests)
RULES: dict[str, dict[str, str]] = {
    "four-bar": {"linkage": "Grashof: shortest + longest < the other two lets the shortest link turn fully; the "
                            "crank shortest, beside the ground, makes a crank-rocker (as here)",
                 "linkage.crank": "mm: input link; the shortest, for a crank that turns fully"},
    "slider-crank": {"linkage": "the crank turns fully while rod >= crank + |offset| (its parts need it); the "
                                "stroke is 2 crank when offset = 0",
                     "linkage.offset": "mm: the slider's line above the crank pivot; a quick return when not 0"},
    "scotch-yoke": {"linkage": "the yoke moves crank (1 - cos theta): simple harmonic motion, a stroke of 2 crank"},
    "whitworth": {"linkage": "ground < crank: the slotted link turns fully, slowly one way and fast the other"},
    "crank-shaper": {"linkage": "ground > crank: the lever swings 2 asin(crank / ground) and the time ratio is "
                                "(180 + that) / (180 - that); lever reaches the ram line"},
    **{kind: {"linkage": f"its canonical proportions in units of size: {rule}"} for kind, rule in _STRAIGHT.items()},
    "gear-pair": {"linkage": "involute spur gears of one module and pressure angle mesh; fewest teeth without "
                             "undercut 2 (1 - shift) / sin^2(pressure_angle) (17 at 20 degrees, no shift); shifted "
                             "pairs mesh at their working centre distance; kind = \"internal\" or \"rack\" (with "
                             "[linkage.slider]) for the other pairs",
                  "linkage.backlash": "mm: play along the pitch circles, each gear's teeth thinned by half of it; "
                                      "about the kerf for a cut pair"},
    "ratchet": {"linkage": "the pawl holds while face_angle + pawl.angle >= atan(friction), the friction angle; "
                           "the lever indexes floor(swing / (360 / teeth)) teeth a stroke"},
    "counter": {"linkage": "the ratchet's rules for the units wheel, whose lever's index must divide its teeth; the "
                           "tens wheel steps 360 / transfer.slots degrees a turn of it, while the units wheel turns "
                           "180 - 360 / slots",
                "linkage.transfer.centre_distance": "mm: the transfer pin stands centre_distance x sin(180 / slots) "
                                                    "from the units wheel's axis, inside its root circle"},
    "oldham": {"linkage": "hub 2 turns exactly with hub 1; the disc's centre runs twice a turn round the circle on "
                          "the shafts' centres as diameter (radius offset / 2); each tongue slides 2 x offset"},
    "trammel": {"linkage": "the tracer's ellipse has semi-axes |rod - point| along X and |point| along Y; the rod's "
                           "midpoint turns like a crank of rod / 2",
                "linkage.point": "mm: the tracer's place on the rod's line from block A; 0 < point < rod inside"},
    "rapson": {"linkage": "tan(tiller) = crosshead / distance; the tiller's torque per unit crosshead force is "
                          "distance / cos^2(tiller), growing towards hard over"},
    "gear-train": {"linkage": "ratio = output speed / input speed: a simple train's -z1/z2 a mesh (idlers set only "
                              "the sense), a compound train's product of its stages; a planetary one's from Willis' "
                              "(w_sun - w_carrier) / (w_ring - w_carrier) = -ring / sun, ring = sun + 2 planet",
                   "linkage.stages": "each stage's [driver, driven] teeth; a stage's driven gear shares its shaft "
                                     "with the next stage's driver"},
    "geared-fivebar": {"linkage": "mobility 3 x moving links - 2 x pins - 1 x gear pairs = 1; a gear pair's centres "
                                  "drawn m (z_a + z_b) / 2 apart"},
    "linkage": {"linkage": "any planar linkage of one input: mobility 3 x moving links - 2 x pins = 1 (a pin "
                           "joining k links counts k - 1), solved a dyad at a time on the assembly the joints draw",
                "linkage.input": "what drives the linkage: a link turning about a pivot (or a slider)"},
    "eight-bar": {"linkage": "mobility 3 x 7 - 2 x 10 = 1; the triad (bar1, bar2, bar3, triad) is one group, solved "
                             "by Newton's method continued from the assembly the joints draw",
                  "linkage.input": "what drives the linkage: a link turning about a pivot (or a slider)"},
}

#: kind -> (what it is, its tables)
STARTERS: dict[str, tuple[str, list[tuple[str, dict[str, Any]]]]] = {
    "four-bar": ("A crank-rocker four-bar with a coupler point tracing a loop.", [
        ("linkage", {"type": "four-bar", "ground": 150.0, "crank": 45.0, "coupler": 135.0, "rocker": 105.0,
                     "point_distance": 60.0, "point_angle": 30.0, "rpm": 60.0}), PARTS]),
    "slider-crank": ("A slider-crank: a crank drives a slider through a connecting rod.", [
        ("linkage", {"type": "slider-crank", "crank": 50.0, "rod": 200.0, "offset": 20.0, "rpm": 120.0}), PARTS]),
    "scotch-yoke": ("A scotch yoke: a pin on the crank slides in a yoke, which moves in pure harmonic motion.", [
        ("linkage", {"type": "scotch-yoke", "crank": 40.0, "rpm": 60.0}), PARTS]),
    "whitworth": ("Whitworth's quick return: a slotted link turning fully drives a ram (analysed; no parts).", [
        ("linkage", {"type": "whitworth", "crank": 60.0, "ground": 30.0, "arm": 50.0, "rod": 150.0, "rpm": 30.0})]),
    "crank-shaper": ("The crank-shaper quick return: a crank swings a slotted lever that drives a ram.", [
        ("linkage", {"type": "crank-shaper", "crank": 50.0, "ground": 150.0, "lever": 250.0, "rpm": 30.0}), PARTS]),
    "chebyshev": ("Chebyshev's straight-line linkage in its canonical proportions.", [
        ("linkage", {"type": "chebyshev", "size": 40.0}), PARTS]),
    "hoekens": ("Hoekens' straight-line linkage in its canonical proportions.", [
        ("linkage", {"type": "hoekens", "size": 40.0}), PARTS]),
    "roberts": ("Roberts' straight-line linkage in its canonical proportions.", [
        ("linkage", {"type": "roberts", "size": 40.0}), PARTS]),
    "watt": ("Watt's straight-line linkage in its canonical proportions.", [
        ("linkage", {"type": "watt", "size": 60.0}), PARTS]),
    "linkage": ("Any planar linkage, drawn: here a crank-rocker whose coupler is a plate carrying the point P.\n"
                "Add joints and links (a dyad at a time) to make six-bars, legs and presses.", [
        ("linkage", {"type": "linkage", "ground": ["O", "Q"], "input": {"link": "crank", "pivot": "O"},
                     "tracers": ["P"], "rpm": 60.0}),
        ("linkage.joints", {"O": [0.0, 0.0], "Q": [150.0, 0.0], "A": [0.0, 45.0], "B": [122.664, 101.379],
                            "P": [34.685, 93.959]}),
        ("linkage.links", {"crank": ["O", "A"], "coupler": ["A", "B", "P"], "rocker": ["Q", "B"]}),
        PARTS]),
    "eight-bar": ("A class-III eight-bar: a crank-rocker's coupler point C drives a triad, the plate E-F-G held by the "
                  "bars C-E, O6-F and O8-G,\nwhich no order of dyads places: it is solved as one group, continued "
                  "from this drawing.", [
        ("linkage", {"type": "linkage", "ground": ["O2", "O4", "O6", "O8"], "input": {"link": "crank", "pivot": "O2"},
                     "tracers": ["C", "E"], "rpm": 60.0}),
        ("linkage.joints", {"O2": [0.0, 0.0], "A": [10.0, 17.320508076], "O4": [80.0, 0.0],
                            "B": [72.221149669, 49.391188359], "C": [28.282302721, 58.244308085],
                            "O6": [144.646417155, 165.096768061], "O8": [19.602606767, 207.097309528],
                            "E": [92.376455415, 130.017651713], "F": [76.116993536, 179.369752979],
                            "G": [41.506551049, 140.612595308]}),
        ("linkage.links", {"crank": ["O2", "A"], "coupler": ["A", "B", "C"], "rocker": ["O4", "B"],
                           "bar1": ["C", "E"], "bar2": ["O6", "F"], "bar3": ["O8", "G"], "triad": ["E", "F", "G"]}),
        PARTS]),
    "geared-fivebar": ("A geared five-bar: two cranks on the frame geared together (40 teeth to 20, module 1.5), "
                       "so the second turns twice, the other way,\nfor each turn of the first; the couplers' point P "
                       "traces the curve. The gear pair is a higher pair: mobility 1.", [
        ("linkage", {"type": "linkage", "ground": ["O2", "O5"], "input": {"link": "crank", "pivot": "O2"},
                     "tracers": ["P"], "rpm": 30.0}),
        ("linkage.joints", {"O2": [0.0, 0.0], "A": [5.0, 8.660254038], "O5": [45.0, 0.0],
                            "B": [36.339745962, 5.0], "C": [22.5, 40.0], "P": [35.0, 50.0]}),
        ("linkage.links", {"crank": ["O2", "A"], "left": ["A", "C", "P"], "right": ["C", "B"],
                           "crank2": ["O5", "B"]}),
        ("linkage.gears.mesh", {"a": {"link": "crank", "centre": "O2", "teeth": 40},
                                "b": {"link": "crank2", "centre": "O5", "teeth": 20}, "module": 1.5,
                                "pressure_angle": 20.0, "backlash": 0.15}),
        ("parts", {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0, "clearance": 0.2, "kerf": 0.15,
                   "sheet": [600.0, 400.0]})]),
    "gear-pair": ("An external pair of involute spur gears: a 12-tooth pinion, shifted clear of undercut, drives a "
                  "30-tooth gear.", [
        ("linkage", {"type": "gear-pair", "kind": "external", "module": 2.0, "pressure_angle": 20.0,
                     "backlash": 0.15, "rpm": 60.0}),
        ("linkage.pinion", {"teeth": 12, "shift": 0.3}),
        ("linkage.gear", {"teeth": 30, "shift": 0.0}),
        PARTS]),
    "ratchet": ("A ratchet and pawl: a 24-tooth wheel held by a sprung pawl and indexed two teeth a stroke by a "
                "lever with a pawl of its own.", [
        ("linkage", {"type": "ratchet", "teeth": 24, "tip_diameter": 80.0, "depth": 6.0, "face_angle": 15.0,
                     "friction": 0.15, "rpm": 30.0}),
        ("linkage.pawl", {"length": 30.0, "angle": 0.0, "spring": 14.0}),
        ("linkage.lever", {"swing": 40.0, "length": 80.0}),
        PARTS]),
    "counter": ("A counter: a 10-tooth ratchet wheel (the units), indexed a tooth a stroke by a lever, steps a "
                "10-slot Geneva wheel (the tens) once a turn through its transfer pin.", [
        ("linkage", {"type": "counter", "teeth": 10, "tip_diameter": 100.0, "depth": 8.0, "face_angle": 16.0,
                     "friction": 0.2, "rpm": 20.0}),
        ("linkage.pawl", {"length": 32.0, "angle": 0.0, "spring": 14.0}),
        ("linkage.lever", {"swing": 40.0, "length": 95.0}),
        ("linkage.transfer", {"slots": 10, "centre_distance": 97.0, "angle": -90.0, "clearance": 0.2}),
        PARTS]),
    "oldham": ("Oldham's coupling: two parallel shafts 20 mm apart turn together through a middle disc whose "
               "tongues slide in both hubs' slots.", [
        ("linkage", {"type": "oldham", "offset": 20.0, "rpm": 60.0}), PARTS]),
    "trammel": ("An elliptic trammel (double slider): two blocks on square guides carry a rod whose tracer draws a "
                "50 by 30 mm ellipse.", [
        ("linkage", {"type": "trammel", "rod": 80.0, "point": 30.0, "rpm": 30.0}), PARTS]),
    "rapson": ("Rapson's slide: a crosshead moving square to the ship's centre line turns the tiller through a "
               "swivel block, with more torque towards hard over.", [
        ("linkage", {"type": "rapson", "distance": 80.0, "max_angle": 35.0, "speed": 10.0}), PARTS]),
    "gear-train": ("A compound gear train of two stages: 18 to 40 teeth, then 18 to 36, a ratio of 0.225.", [
        ("linkage", {"type": "gear-train", "kind": "compound", "module": 2.0, "pressure_angle": 20.0,
                     "stages": [[18, 40], [18, 36]], "backlash": 0.15, "rpm": 60.0}), PARTS]),
}


def _sub_model(model: type[BaseModel], table: str) -> type[BaseModel] | None:
    """The model of ``linkage.KEY``'s table (``KEY`` a field of ``model`` holding a model, or an optional one), or
    None."""
    head, _, key = table.partition(".")
    key, _, named = key.partition(".")          # linkage.gears.NAME: a model of a table of named ones
    info = model.model_fields.get(key) if head == "linkage" else None
    kinds = get_args(info.annotation)[1:] if info is not None and named else \
        (info.annotation, *get_args(info.annotation)) if info is not None else ()
    for kind in kinds:
        if isinstance(kind, type) and issubclass(kind, BaseModel):
            return kind
    return None


def starter(kind: str, name: str) -> str:
    """The starter template of ``kind`` (a mechanism type) named ``name``, as TOML text; a one-line
    :class:`~camgen.core.errors.SpecError` naming ``KIND`` for another."""
    kind = choose(kind, STARTERS, "KIND")
    what, tables = STARTERS[kind]
    mechanism = str(tables[0][1]["type"])          # a named example of a type (eight-bar) starts as that type
    build = "" if kind == "whitworth" else f"\nCut and print its parts with:  linkgen build {name}.toml"
    header = (f"{what}\nAnalyse it with:  linkgen analyze {name}.toml   (files land in out/{name}/){build}\n"
              "Every key is explained in the documentation's template reference; --set KEY=VALUE changes one for a "
              "run.")
    models = {"linkage": MECHANISMS[mechanism].table, "parts": PartsTable,
              **{table: model for table, _ in tables if (model := _sub_model(MECHANISMS[mechanism].table, table))}}
    return render(header, [("", {"name": name}), *tables], models, {**NOTES, **RULES.get(kind, RULES[mechanism])})
