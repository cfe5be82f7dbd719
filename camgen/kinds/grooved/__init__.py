"""Grooved face (track) cams: design (:mod:`camgen.kinds.grooved.design`) and files
(:mod:`camgen.kinds.grooved.outputs`).

The roller runs in a groove in the cam's face, between an inner and an outer flank: the exact
offsets of the pitch curve by -(Rr + c/2) and +(Rr + c/2) (Rr the roller radius, c
``cam.running_clearance``), so the cam drives the follower both ways without a spring.
"""
from .kind import KIND as KIND
