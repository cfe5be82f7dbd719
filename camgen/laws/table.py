"""The standard comparison of laws for h = beta = 1, computed from the laws themselves."""
from __future__ import annotations

from typing import Any

from camgen.laws import TABLE_LAWS, make_law


def law_table() -> list[dict[str, Any]]:
    """One row per law: peak |f'|, |f''|, |f'''| over the segment and which become infinite between dwells.

    ``modified-uniform`` is its default blended form (cycloidal blends over 0.25 of
    the angle at each end); ``parabolic`` has acceleration ratio 1.
    """
    rows = []
    for name in TABLE_LAWS:
        law = make_law(name)
        cv, ca, cj = (float(x) for x in law.peaks())
        rows.append({"law": name, "cv": cv, "ca": ca, "cj": cj, "infinite": law.infinite()})
    return rows
