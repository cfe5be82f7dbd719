"""The disc cam (``cam.kind = "disc"``, the default): a plate turning about its centre, cut to a profile.

Its design and files are the flat cams' (:mod:`camgen.flat`, :mod:`camgen.outputs`); the package holds its kind
(:mod:`~camgen.kinds.disc.kind`) and its ``camgen new`` starters (:mod:`~camgen.kinds.disc.starters`).
"""
from .kind import KIND as KIND
