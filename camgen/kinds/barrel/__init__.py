"""Barrel (cylindrical) cams: a groove round a cylinder drives a roller along the cam's axis.

:mod:`~camgen.barrel.walls` (the groove's exact walls, numpy only), :mod:`~camgen.barrel.design` (checks, the
developed drawing, the solid) and :mod:`~camgen.barrel.outputs` (the files).
"""
