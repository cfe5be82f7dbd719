"""linkgen: planar linkages, their kinematics and their parts."""
