"""Speed against accuracy (docs/tradeoff.md, The command): ``workbook-gen tradeoff SCENE``.

    from workbook_gen.tradeoff import measure, write_tradeoff_workbook, format_table
    result = measure(load_scene("templates/sewing_machine.toml"))
    print(format_table(result)); result.to_json()["rows"]
    write_tradeoff_workbook(result, "outputs")     # outputs/<name>_tradeoff.xlsx

Modules: ``reference50`` (the scene's trees at 50 digits, true extremes),
``steps`` (step and derivative dimensions), ``methods`` (closed form against
Newton or halving), ``precision`` (float64 against 50 digits), ``rates``
(which positions differentiate to which rate columns), ``variants`` (the scene
with another step, options or outputs), ``report`` (terminal table), ``book`` (the Tradeoff workbook).
"""

from .book import write_tradeoff_workbook
from .common import Row
from .measure import Tradeoff, measure, progress_steps
from .report import format_table

__all__ = ["measure", "progress_steps", "Tradeoff", "Row", "format_table",
           "write_tradeoff_workbook"]
