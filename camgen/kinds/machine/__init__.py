"""Machines: several cams on phased shafts, each cam's follower arm driving a four-bar, one timing diagram.

A machine template (its own ``[machine]`` table, ``camgen build machine.toml``) names its shafts (fixed pivots on
a frame, the main shaft the input at ``machine.rpm``), gear pairs between shafts, the cams mounted on them (each an
inline cam template or a path to one, at a phase and a layer), the linkages (likewise, linkgen templates) and the
couplings: a cam's oscillating follower arm as a four-bar's crank; a linkage may instead be turned by a crank on
a shaft.

* :mod:`~camgen.kinds.machine.spec`: the template, validated (every cross-reference checked, one line naming the field);
* :mod:`~camgen.kinds.machine.kinematics`: the composition, pure numpy (chain rule, dwells and overlaps, virtual work);
* :mod:`~camgen.kinds.machine.design`: every cam designed by its kind, every output over one turn, checks and forces;
* :mod:`~camgen.kinds.machine.cranked`: a linkage turned by a crank on a shaft, at a phase;
* :mod:`~camgen.kinds.machine.clash`: every part placed over the turn, and the parts that meet;
* :mod:`~camgen.kinds.machine.poses`: every part's pose and every named point at any main shaft angles;
* :mod:`~camgen.kinds.machine.report`, :mod:`~camgen.kinds.machine.plots` (the timing diagram, the machine at chosen
  angles), :mod:`~camgen.kinds.machine.page` (the animated page), :mod:`~camgen.kinds.machine.outputs`: the files;
* :mod:`~camgen.kinds.machine.kind`: its entry in the kind registry (:data:`camgen.kinds.KINDS`).
"""
from .kind import KIND as KIND
