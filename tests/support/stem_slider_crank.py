"""A slider-crank a translating follower's stem lifts, as a machine template's text: the slider C (the stem's
point, sliding along +Y from the origin), the rod A-C and the crank O-A about O = (50, 60) mm, the crank carrying
an output torque of 1.5 N m. Shared by the machine tests that couple a stem (a disc cam's, a conjugate yoke's) to a
linkage."""
from __future__ import annotations


def stem_slider_crank(cam: str) -> str:
    """The ``[[linkages]]`` entry "rocker" and the ``[[couplings]]`` entry coupling cam ``cam``'s stem to its
    slider, as TOML text to append to a machine template."""
    return f"""[[linkages]]
name = "rocker"

[linkages.template.linkage]
type = "linkage"
ground = ["O"]
input = {{ slider = "stem" }}
tracers = ["A"]

[linkages.template.linkage.joints]
C = [0.0, 0.0]
O = [50.0, 60.0]
A = [24.684032711, 76.096639408]

[linkages.template.linkage.links]
crank = ["O", "A"]
rod = ["A", "C"]

[linkages.template.linkage.sliders.stem]
point = "C"
guide = "ground"
angle = 90.0

[linkages.template.parts]
width = 8.0
thickness = 3.0
pin_diameter = 3.0

[[couplings]]
cam = "{cam}"
linkage = "rocker"
link = "stem"
rest = 0.0
output = "crank"
output_torque = 1.5
"""
