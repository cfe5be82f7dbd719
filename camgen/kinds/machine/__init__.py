"""Machines: several cams on phased shafts, each cam's follower arm driving a four-bar, one timing diagram.

A machine template (its own ``[machine]`` table, ``camgen build machine.toml``) names its shafts (fixed pivots on
a frame, the main shaft the input at ``machine.rpm``), gear pairs between shafts, the cams mounted on them (each an
inline cam template or a path to one, at a phase and a layer), the linkages (likewise, linkgen templates) and the
couplings: a cam's oscillating follower arm as a four-bar's crank.

* :mod:`~camgen.machine.spec`: the template, validated (every cross-reference checked, one line naming the field);
* :mod:`~camgen.machine.motion`: the composition, pure numpy (chain rule, dwells and overlaps, virtual work);
* :mod:`~camgen.machine.design`: every cam designed by its kind, every output over one turn, checks and forces;
* :mod:`~camgen.machine.report`, :mod:`~camgen.machine.plots`, :mod:`~camgen.machine.outputs`: the files;
* :mod:`~camgen.machine.kind`: its entry in the kind registry (:data:`camgen.kinds.KINDS`).
"""
