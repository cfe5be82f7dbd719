"""The plate (linear) cam (``cam.kind = "plate"``): a plate sliding along +X, cut to a profile.

Its design and files are the flat cams' (:mod:`camgen.flat`, :mod:`camgen.outputs`); the package holds its kind
(:mod:`~camgen.kinds.plate.kind`) and its ``camgen new`` starter (:mod:`~camgen.kinds.plate.starters`).
"""
from .kind import KIND as KIND
