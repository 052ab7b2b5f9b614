"""The Statistics sheet of a random study's summary.xlsx (docs/batch.md, summary.xlsx): for every
output extreme, span and numeric figure, its spread over the ok variants and each varied parameter's
effect on it, with a Sensitivity chart of the effects.

Every statistic is a live formula over the Variants sheet that Excel and LibreOffice
both compute, an array formula filtering the ok variants (``IF(status="ok", column)``:
partial variants, whose extremes leave rows out, and refused ones are left out):
AVERAGE, STDEV.S, MIN, MAX, PERCENTILE.INC (5, 50, 95 %), CORREL.  The effect is the
standardised regression coefficient (SRC) of a linear fit over the same variants,
``SRC = r R^-1`` (``r``: the output's correlations with the parameters, ``R``: the
parameters' correlation matrix, on the sheet; each SRC cell
``INDEX(MMULT(r, MINVERSE(R)), 1, j)``), and ``R^2 = r . SRC`` says how much of the
output's variance the fit explains.  The cached values are numpy's over the same
numbers (``np.percentile``'s linear rule is PERCENTILE.INC's).

A column that does not vary (its spread within 1e-6 of its size: rounding, whose
correlations are noise) gets its statistics and the text ``constant`` for its effects.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..cellref import a1, column_letters
from .rows import figure_columns
from .table import Table

SHEET = "Statistics"
_HEAD = 5                  # the header row (0-based); the notes above it
_STATS = (("n", "COUNT"), ("mean", "AVERAGE"), ("standard deviation", "_xlfn.STDEV.S"),
          ("min", "MIN"), ("5th percentile", 0.05), ("median", 0.5),
          ("95th percentile", 0.95), ("max", "MAX"))
_CONSTANT = 1e-6            # relative spread below which a column is taken as constant
NOTES = (
    "Statistics of the random variants over the ok ones (status ok); partial variants "
    "(their extremes leave rows out) and refused ones are left out. Live formulas over "
    "the Variants sheet.",
    "Effect: the standardised regression coefficient (SRC) of each varied parameter, "
    "from a linear fit over the same variants: how many standard deviations the output "
    "moves for one standard deviation of the parameter, the others held. "
    "SRC = r R^-1, r: the correlations (Pearson) of the output with the parameters, "
    "R: the parameters' correlations (below the table).",
    "R^2 = r . SRC: the share of the output's variance the linear fit explains; where it "
    "is well below 1 the effects are not linear and the SRCs say less. "
    "'constant': the output varies by less than 1e-6 of its size.",
)


@dataclass(frozen=True)
class Column:
    name: str          # the summary column
    unit: str
    letter: str        # its column on the Variants sheet
    values: np.ndarray  # its values over the ok variants
    constant: bool


def stat_columns(table: Table, ok: np.ndarray) -> list[Column]:
    """The columns the sheet describes: each output's min and max, the spans and the
    numeric figures, where every ok variant has a number."""
    model = table.model
    names = []
    for q in model.outputs():
        names += [f"{q.name}_min", f"{q.name}_max"]
    names += [c for c in figure_columns(model) if table.kind(c) == "number"]
    out = []
    for name in names:
        values = np.array([np.nan if v is None or isinstance(v, str) else v
                           for v in table.data[name]], dtype=float)[ok]
        if not np.isfinite(values).all():
            continue
        size = float(np.abs(values).max())
        spread = float(values.max() - values.min())
        out.append(Column(name, table.units.get(name, ""),
                          column_letters(table.columns.index(name) + 1), values,
                          spread <= _CONSTANT * size))
    return out


def _stat_value(values: np.ndarray, how) -> float:
    if how == "COUNT":
        return float(len(values))
    if how == "AVERAGE":
        return float(np.mean(values))
    if how == "_xlfn.STDEV.S":
        return float(np.std(values, ddof=1))
    if how == "MIN":
        return float(values.min())
    if how == "MAX":
        return float(values.max())
    return float(np.percentile(values, 100 * how))


def write_statistics(book, table: Table) -> None:
    """The Statistics sheet and its Sensitivity chart, for a random study with at least
    three ok variants (and two more than its varied parameters for the effects)."""
    design = table.design
    if design.kind != "random":
        return
    ok = np.array([s == "ok" for s in table.statuses()], dtype=bool)
    count = int(ok.sum())
    columns = stat_columns(table, ok) if count >= 3 else []
    sheet = book.add_worksheet(SHEET)
    bold = book.add_format({"bold": True})
    head = book.add_format({"bold": True, "bottom": 1, "text_wrap": True, "valign": "top"})
    sheet.set_column(0, 0, 22)
    sheet.set_column(1, 1, 9)
    sheet.set_column(2, 2, 6)
    k = len(design.names)
    first_src = len(_STATS) + 2                 # the effects' first column
    fixed = book.add_format({"num_format": "0.000"})
    sheet.set_column(3, first_src - 1, 11, book.add_format({"num_format": "#,##0.0###"}))
    sheet.set_column(first_src, first_src + 2 * k, 9, fixed)
    sheet.write_string(0, 0, "Statistics", bold)
    for row, note in enumerate(NOTES, start=1):
        sheet.write_string(row, 0, note)
    if not columns:
        sheet.write_string(_HEAD - 1, 0, f"{count} ok variants: too few for statistics")
        return
    last = len(design) + 1
    status = f'Variants!$C$2:$C${last}="ok"'

    def rng(letter: str) -> str:
        return f"Variants!${letter}$2:${letter}${last}"

    params = list(design.names)
    p_letters = [column_letters(table.columns.index(p) + 1) for p in params]
    p_values = [np.array(table.data[p], dtype=float)[ok] for p in params]
    effects = count >= k + 2
    r_col = first_src + k + 1
    labels = (["quantity", "unit"] + [s for s, _ in _STATS]
              + ([f"SRC {p}" for p in params] + ["R^2"] + [f"r {p}" for p in params]
                 if effects else []))
    sheet.set_row(_HEAD, 30)
    sheet.write_row(_HEAD, 0, labels, head)
    sheet.freeze_panes(_HEAD + 1, 1)
    top = _HEAD + 1
    matrix_row = top + len(columns) + 2          # the parameters' correlation matrix
    R = np.atleast_2d(np.corrcoef(np.vstack(p_values))) if effects else None
    matrix = (f"{a1(matrix_row + 3, 2, True)}:"
              f"{a1(matrix_row + 2 + k, k + 1, True)}")
    cached: list[list] = []  # each column's SRCs (None where "constant"), for the chart
    for i, column in enumerate(columns):
        row = top + i
        cached.append([None] * k)
        sheet.write_string(row, 0, column.name)
        sheet.write_string(row, 1, column.unit)
        inside = f"IF({status},{rng(column.letter)})"
        for j, (_, how) in enumerate(_STATS):
            formula = (f"{how}({inside})" if isinstance(how, str)
                       else f"_xlfn.PERCENTILE.INC({inside},{how})")
            _array(sheet, row, 2 + j, "{=" + formula + "}", _stat_value(column.values, how))
        if not effects:
            continue
        if column.constant:
            for j in range(2 * k + 1):
                sheet.write_string(row, first_src + j, "constant")
            continue
        r = np.array([np.corrcoef(x, column.values)[0, 1] for x in p_values])
        src = np.linalg.solve(R, r)
        cached[-1] = [float(v) for v in src]
        r_row = (f"{a1(row + 1, r_col + 1, True)}:"
                 f"{a1(row + 1, r_col + k, True)}")
        for j in range(k):
            _array(sheet, row, first_src + j,
                   f"{{=INDEX(MMULT({r_row},MINVERSE({matrix})),1,{j + 1})}}", float(src[j]))
        sheet.write_formula(row, first_src + k,
                            f"=SUMPRODUCT({r_row},{a1(row + 1, first_src + 1)}:"
                            f"{a1(row + 1, first_src + k)})",
                            None, float(r @ src))
        for j in range(k):
            _array(sheet, row, r_col + j,
                   f"{{=CORREL(IF({status},{rng(p_letters[j])}),{inside})}}", float(r[j]))
    if not effects:
        return
    sheet.write_string(matrix_row, 0, "correlations of the varied parameters", bold)
    sheet.write_row(matrix_row + 1, 1, params, head)
    for i in range(k):
        sheet.write_string(matrix_row + 2 + i, 0, params[i], bold)
        for j in range(k):
            _array(sheet, matrix_row + 2 + i, 1 + j,
                   f"{{=CORREL(IF({status},{rng(p_letters[i])}),"
                   f"IF({status},{rng(p_letters[j])}))}}", float(R[i, j]), fixed)
    _sensitivity_chart(book, sheet, columns, params, top, first_src, r_col + k + 1, cached)


def _array(sheet, row: int, col: int, formula: str, value: float, style=None) -> None:
    sheet.write_array_formula(row, col, row, col, formula, style, value)


def _sensitivity_chart(book, sheet, columns: list[Column], params: list[str], top: int,
                       first_src: int, at_col: int, cached: list[list]) -> None:
    """A bar chart of the SRCs: one bar per parameter for each output, in the table's
    order from the top; ``cached``: the SRCs per output, which the chart caches."""
    chart = book.add_chart({"type": "bar"})
    last = top + len(columns) - 1
    palette = ("#1F77B4", "#D62728", "#2CA02C", "#9467BD", "#FF7F0E", "#8C564B",
               "#E377C2", "#7F7F7F", "#BCBD22", "#17BECF")
    for j, p in enumerate(params):
        colour = palette[j % len(palette)]
        chart.add_series({
            "name": [SHEET, _HEAD, first_src + j],
            "categories": [SHEET, top, 0, last, 0],
            "values": [SHEET, top, first_src + j, last, first_src + j],
            "name_data": [p], "categories_data": [c.name for c in columns],
            "values_data": [src[j] for src in cached],
            "fill": {"color": colour}, "border": {"color": colour},
        })
    grid = {"visible": True, "line": {"color": "#D9D9D9"}}
    chart.set_title({"name": "Sensitivity: standardised regression coefficients",
                     "name_font": {"size": 11}})
    chart.set_x_axis({"name": "SRC (output standard deviations per parameter standard "
                              "deviation)", "major_gridlines": grid})
    chart.set_y_axis({"reverse": True, "label_position": "low", "interval_unit": 1})
    chart.set_legend({"position": "bottom"})
    chart.set_size({"width": 620, "height": 120 + 16 * len(columns) * max(1, len(params))})
    sheet.insert_chart(_HEAD, at_col, chart)
