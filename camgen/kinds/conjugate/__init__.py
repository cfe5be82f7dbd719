"""Conjugate (dual) cams: two discs on one shaft, each driving one of the two rollers of one follower.

:mod:`~camgen.conjugate.followers` (the second roller's path, numpy only), :mod:`~camgen.conjugate.design` (both
cams built and checked as a matched pair) and :mod:`~camgen.conjugate.outputs` (the files).
"""
