"""Conjugate (dual) cams: two discs on one shaft, each driving one of the two rollers of one follower.

:mod:`~camgen.kinds.conjugate.kinematics` (the second roller's path, numpy only),
:mod:`~camgen.kinds.conjugate.design` (both cams built and checked as a matched pair) and
:mod:`~camgen.kinds.conjugate.outputs` (the files).
"""
from .kind import KIND as KIND
