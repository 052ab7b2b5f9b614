"""Reading xlsx files safely: cells, cached values, formula text, names, links."""

from workbook_gen.xlsx.model import (
    Cell,
    ExternalLink,
    SharedFormula,
    Sheet,
    Workbook,
    column_letters,
)
from workbook_gen.xlsx.reader import read_workbook

__all__ = [
    "Cell",
    "ExternalLink",
    "SharedFormula",
    "Sheet",
    "Workbook",
    "column_letters",
    "read_workbook",
]
