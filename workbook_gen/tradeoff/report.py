"""The tradeoff on the terminal: a readable table (the progress bar is
``workbook_gen.progress``)."""

from __future__ import annotations

from .measure import Tradeoff

_HEAD = ("dimension", "setting", "max error", "seconds", "CPU s", "cells", "bytes", "note")


def _error(x: float | None) -> str:
    return "-" if x is None else f"{x:.2e}"


def _seconds(x: float | None) -> str:
    return "-" if x is None else f"{x:.3f}" if x < 10 else f"{x:.1f}"


def _count(x: int | None) -> str:
    return "-" if x is None else f"{x:,}"


def format_table(result: Tradeoff) -> str:
    """The rows as aligned text, a blank line between dimensions."""
    scene = result.scene
    lines = [f"{scene.name} ({scene.template.id}): speed against accuracy",
             "max error: worst over the outputs, relative to the output's magnitude, against "
             "the formulas at 50 digits (mpmath)",
             "seconds: generate + audit the workbook (precision: evaluate the table), wall "
             "time; CPU s: the process time of the same work (not inflated by other load)", ""]
    body = [(r.dimension, r.setting, _error(r.max_error), _seconds(r.seconds),
             _seconds(r.cpu_seconds), _count(r.cells),
             _count(r.bytes), r.note) for r in result.rows]
    widths = [max(len(row[i]) for row in body + [_HEAD]) for i in range(len(_HEAD) - 1)]
    right = {2, 3, 4, 5, 6}

    def fmt(row) -> str:
        cells = [row[i].rjust(w) if i in right else row[i].ljust(w) for i, w in enumerate(widths)]
        return "  ".join(cells + [row[-1]]).rstrip()

    lines += [fmt(_HEAD), "  ".join("-" * w for w in widths)]
    previous = None
    for row in body:
        if previous is not None and row[0] != previous:
            lines.append("")
        lines.append(fmt(row))
        previous = row[0]
    cpu = "" if result.cpu_seconds is None else f" ({result.cpu_seconds:.1f} s CPU)"
    lines.append(f"\nmeasured in {result.seconds:.1f} s{cpu}")
    return "\n".join(lines)

