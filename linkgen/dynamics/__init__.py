"""A linkage's dynamics (``[dynamics]``): masses from its parts as made, Newton-Euler at a speed, the flywheel and
the counterweight of a crank, and whether its holes and pins hold.

* :mod:`~linkgen.dynamics.table`: the ``[dynamics]`` table;
* :mod:`~linkgen.dynamics.materials`: densities and allowables, with their sources;
* :mod:`~linkgen.dynamics.section`: a flat part's area, centroid and second moment, exact for its arcs;
* :mod:`~linkgen.dynamics.masses`: each moving link's mass, centre and inertia, its pins and hardware added;
* :mod:`~linkgen.dynamics.run`: the dynamics over the motion (the kernels are :mod:`linkgen.kinematics.inertia`,
  :mod:`linkgen.kinematics.kinetostatics` and :mod:`linkgen.kinematics.balance`, pure numpy);
* :mod:`~linkgen.dynamics.profile`: the input's speed over the motion (constant, a profile through rows, or the
  motor's steady turn);
* :mod:`~linkgen.dynamics.flywheel`: the flywheel's plates; :mod:`~linkgen.dynamics.strength`: the holes and pins;
* :mod:`~linkgen.dynamics.report` and :mod:`~linkgen.dynamics.plots`: the report's section and the figures.
"""
