"""The six-bar types the six-bar path search draws (:mod:`linkgen.synthesis.sixbar`): each one's joints, links,
crank and tracer.

Every type is a crank O2-A (the link ``crank``, turning about O2 on the ground) with the ground pivot O4 on +X of
it in the normalised drawing, and is solved by the general solver dyad by dyad. The names follow the bundled
templates (``templates/watt1.toml`` ... ``stephenson3.toml``); textbooks number the Stephenson inversions
differently, so each is stated by its drawing here:

* **watt1** (Watt I: the two ternary links share a joint, the ground is binary): the four-bar O2-A-B-O4 with a
  ternary coupler (A, B, E) and a ternary rocker (O4, B, F); the dyad E-G-F between them; the tracer P on the
  output F-G.
* **watt2** (Watt II: the ground is ternary and shares O4 with the other ternary link): two four-bars in series,
  O2-A-B-O4 and O4-C-D-O6, through the ternary rocker (O4, B, C); the tracer P on the rod C-D.
* **stephenson1** (Stephenson I: the ground is the binary link joining the two ternary links): the ternary crank
  (O2, A, E) and the ternary rocker (O4, B, F) joined by the coupler A-B (a four-bar) and by the dyad E-G-F; the
  tracer P on the rod E-G.
* **stephenson3** (Stephenson III: the ground and the coupler are the ternary links): the four-bar O2-A-B-O4 with a
  ternary coupler (A, B, C) and the dyad C-D-O6 to a third ground pivot; the tracer P on the rod C-D.

Stephenson II (the ground a binary link next to one ternary link only) needs a class-III group whichever link
next to the ground is the crank, which the general solver places by Newton continuation per design
(:mod:`linkgen.kinematics.groups`): too slow inside a search. :data:`STEPHENSON2` is searched by its own module
(:mod:`linkgen.synthesis.stephenson2`, its triad by :mod:`linkgen.synthesis.sixbar_triad`):

* **stephenson2** (Stephenson II: the ground binary, next to the ternary crank and to a binary only): the ternary
  crank (O2, A, E) and the triad, the plate (C, D, F) held by the rods A-C and E-D and the rocker O4-F; the tracer
  P on the plate.
"""
from __future__ import annotations

from dataclasses import dataclass

from linkgen.kinematics.structure import Input


@dataclass(frozen=True)
class Topology:
    """A six-bar's drawing: the free joints (searched), the links (name -> joints; the tracer P last on its
    link), the ground pivots, the tracer's link and the joint it is placed from."""

    name: str
    free: tuple[str, ...]
    links: dict[str, tuple[str, ...]]
    ground: tuple[str, ...]
    tracer_link: str
    reference: str


TOPOLOGIES = {
    "watt1": Topology("watt1", ("A", "B", "E", "F", "G"),
                      {"crank": ("O2", "A"), "coupler": ("A", "B", "E"), "rocker": ("O4", "B", "F"),
                       "output": ("F", "G", "P"), "rod": ("E", "G")}, ("O2", "O4"), "output", "F"),
    "watt2": Topology("watt2", ("A", "B", "C", "O6", "D"),
                      {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B", "C"),
                       "rod": ("C", "D", "P"), "output": ("O6", "D")}, ("O2", "O4", "O6"), "rod", "C"),
    "stephenson1": Topology("stephenson1", ("A", "B", "E", "F", "G"),
                            {"crank": ("O2", "A", "E"), "coupler": ("A", "B"), "rocker": ("O4", "B", "F"),
                             "rod": ("E", "G", "P"), "output": ("F", "G")}, ("O2", "O4"), "rod", "E"),
    "stephenson3": Topology("stephenson3", ("A", "B", "C", "O6", "D"),
                            {"crank": ("O2", "A"), "coupler": ("A", "B", "C"), "rocker": ("O4", "B"),
                             "rod": ("C", "D", "P"), "output": ("O6", "D")}, ("O2", "O4", "O6"), "rod", "C"),
}
#: the Stephenson II (searched by :mod:`linkgen.synthesis.stephenson2`, not among :data:`SIXBARS`)
STEPHENSON2 = Topology("stephenson2", ("A", "E", "C", "D", "F"),
                       {"crank": ("O2", "A", "E"), "rod1": ("A", "C"), "rod2": ("E", "D"),
                        "plate": ("C", "D", "F", "P"), "rocker": ("O4", "F")}, ("O2", "O4"), "plate", "F")
#: the six-bar types searched, as ``task.linkage`` names them
SIXBARS = tuple(TOPOLOGIES)
CRANK = (Input("crank", "crank", "O2"),)
