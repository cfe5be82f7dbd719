"""Geneva drives (intermittent indexing): a template with a ``[geneva]`` table.

A driver turning at constant speed carries a pin on a crank of radius a and a locking disc;
the wheel has n radial slots and n concave locking arcs. The pin enters a slot tangentially
(radial entry, a = C sin(pi / n), C the centre distance), turns the wheel by 2 pi / n while
the driver turns pi - 2 pi / n, and leaves; the locking disc then holds the wheel still for
the rest of the driver's turn. Modules, in the order data flows: :mod:`~camgen.kinds.geneva.table`
(the template), :mod:`~camgen.kinds.geneva.kinematics` (the Geneva law, numpy only),
:mod:`~camgen.kinds.geneva.geometry` (the parts' exact outlines), :mod:`~camgen.kinds.geneva.assembly`
(clearances over a whole turn), :mod:`~camgen.kinds.geneva.design`, :mod:`~camgen.kinds.geneva.report`,
:mod:`~camgen.kinds.geneva.plots` and :mod:`~camgen.kinds.geneva.outputs` (the files).
"""
from .kind import KIND as KIND
