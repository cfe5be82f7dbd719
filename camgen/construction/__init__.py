"""The graphical construction of a disc cam's profile as the course teaches it (the inversion method): the
cam held still and the follower turned round it the other way, station by station, its displacement
transferred from the displacement diagram. :mod:`~camgen.construction.geometry` makes the construction's
points as data (pure numpy); :mod:`~camgen.construction.figure` draws them (``camgen build --construction``).
"""
