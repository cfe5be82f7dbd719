"""Write a linkage analysis: the JSON report and the plots, all-or-nothing (see camgen.parts.files)."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from camgen.parts.files import staged
from camgen.report import report_json
from linkgen.analyze import build_linkage
from linkgen.fourbar import FourBar


def write_analysis(template: Any, report: dict[str, Any], directory: str | Path) -> dict[str, str]:
    """Write the files ``output.formats`` asks for; return their names by kind."""
    formats = set(template.output.formats)
    name, spec = template.name, template.linkage
    files: dict[str, str] = {}
    with staged(directory) as stage:
        plots = [f for f in ("png", "svg") if f in formats]
        if plots:
            from linkgen import plots as lp

            mech = build_linkage(spec)
            fb = mech if isinstance(mech, FourBar) else getattr(mech, "linkage", None)
            assembly = getattr(spec, "assembly", getattr(mech, "assembly", "open"))
            if fb is not None:
                figures = {"transmission": lp.transmission_figure(name, fb, assembly),
                           "dead-centres": lp.dead_centre_figure(name, fb, assembly)}
            else:
                figures = {"motion": lp.slider_figure(name, mech, spec.rpm * 2 * math.pi / 60)}
            for kind, fig in figures.items():
                for fmt in plots:
                    files[f"{kind}_{fmt}"] = stage.write(
                        f"{name}-{kind}.{fmt}", lambda p, fig=fig, fmt=fmt: fig.savefig(p, format=fmt, dpi=120)).name
        if "json" in formats:
            files["json"] = f"{name}.json"
            stage.write(f"{name}.json", lambda p: p.write_text(report_json({**report, "files": files}),
                                                                  encoding="utf-8"))
    return files
