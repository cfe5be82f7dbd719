"""Linkage kinematics: closed-form positions, velocities, accelerations and dead centres, vectorised over
arrays of input angles.

Pure numpy (scipy and math allowed): no spec, no parts, no files, no plots; errors from
:mod:`camgen.core.errors` only. Lengths in mm, angles in radians, counter-clockwise from the
ground line (+X) with the input pivot at the origin; each module states its own frame.

* :mod:`~linkgen.kinematics.grashof`: Grashof class and inversion of a four-bar chain;
* :mod:`~linkgen.kinematics.fourbar`: the four-bar, exact up to its toggles;
* :mod:`~linkgen.kinematics.circuits`: a four-bar's circuits, and each link's limits and swing on them;
* :mod:`~linkgen.kinematics.slidercrank`: slider-crank and scotch yoke;
* :mod:`~linkgen.kinematics.quickreturn`: crank-shaper and Whitworth quick returns;
* :mod:`~linkgen.kinematics.straightline`: Chebyshev, Hoekens, Roberts and Watt straight-line linkages.
"""
