"""Geneva drives (intermittent indexing): a template with a ``[geneva]`` table.

A driver turning at constant speed carries a pin on a crank of radius a and a locking disc;
the wheel has n radial slots and n concave locking arcs. The pin enters a slot tangentially
(radial entry, a = C sin(pi / n), C the centre distance), turns the wheel by 2 pi / n while
the driver turns pi - 2 pi / n, and leaves; the locking disc then holds the wheel still for
the rest of the driver's turn. Modules, in the order data flows: :mod:`~camgen.geneva.spec`
(the template), :mod:`~camgen.geneva.kinematics` (the Geneva law, numpy only),
:mod:`~camgen.geneva.geometry` (the parts' exact outlines), :mod:`~camgen.geneva.assembly`
(clearances over a whole turn), :mod:`~camgen.geneva.design`, :mod:`~camgen.geneva.report`,
:mod:`~camgen.geneva.plots` and :mod:`~camgen.geneva.outputs` (the files).
"""
