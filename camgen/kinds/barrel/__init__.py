"""Barrel (cylindrical) cams: a groove round a cylinder drives a roller along the cam's axis.

:mod:`~camgen.kinds.barrel.kinematics` (the groove's exact walls, numpy only), :mod:`~camgen.kinds.barrel.design`
(checks, the developed drawing, the solid) and :mod:`~camgen.kinds.barrel.outputs` (the files).
"""
from .kind import KIND as KIND
