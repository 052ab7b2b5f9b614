"""Cached against recomputed: Excel-aware tolerances, per-column statistics.

``|a - b| <= max(REL * |a|, ABS * scale)`` where ``scale`` is the magnitude of
the formula's operands: Excel and LibreOffice store 15 significant digits and
round a difference that is tiny against its operands to 0, so a workbook they
saved must pass.  Error values must match exactly; so must text and booleans.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..xlerror import ExcelError

REL = 1e-10
ABS = 1e-10


def _allowance(cached, magnitude):
    """The difference tolerated: REL of the cached value or ABS of the magnitude
    (value or operands); scalars and arrays alike."""
    return np.maximum(REL * np.abs(cached), ABS * magnitude)


@dataclass
class Verdict:
    agree: bool
    abs_error: float = 0.0
    rel_error: float = 0.0


def _number(value: object) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value)


def compare(cached: object, recomputed: object, scale: float) -> Verdict:
    """Does ``recomputed`` explain ``cached``?"""
    a, b = _number(cached), _number(recomputed)
    if a is not None and b is not None:
        if not (math.isfinite(a) and math.isfinite(b)):
            return Verdict(a == b)
        diff = abs(a - b)
        # relative to the larger of the value and the formula's operands: a residual of
        # 1e-16 recomputed as 3e-16 from operands of 100 is rounding, not a 200% error
        magnitude = max(abs(a), abs(b), scale)
        rel = diff / magnitude if magnitude else 0.0
        return Verdict(bool(diff <= _allowance(a, magnitude)), diff, rel)
    if isinstance(cached, ExcelError) or isinstance(recomputed, ExcelError):
        return Verdict(cached == recomputed)
    # An empty cached string and an empty text result are the same to every reader.
    if cached in (None, "") and recomputed in (None, ""):
        return Verdict(True)
    if isinstance(cached, bool) or isinstance(recomputed, bool):
        return Verdict(type(cached) is type(recomputed) and cached == recomputed)
    return Verdict(cached == recomputed)


@dataclass
class ColumnStats:
    sheet: str
    column: str
    cells: int = 0
    mismatches: int = 0
    worst_error: float = 0.0   # relative error (absolute where the value is 0)
    worst_cell: str = ""

    def add_many(self, refs, agree: np.ndarray, rel: np.ndarray) -> None:
        """Many cells at once; ``refs(i)`` names the i-th (asked for the worst only)."""
        self.cells += len(agree)
        self.mismatches += int((~agree).sum())
        if len(agree):
            i = int(np.argmax(rel))
            if rel[i] > self.worst_error:
                self.worst_error, self.worst_cell = float(rel[i]), refs(i)

    def add(self, ref: str, verdict: Verdict) -> None:
        self.cells += 1
        self.mismatches += not verdict.agree
        error = verdict.rel_error if math.isfinite(verdict.rel_error) else verdict.abs_error
        if error > self.worst_error:
            self.worst_error, self.worst_cell = error, ref


def compare_numbers(cached: np.ndarray, recomputed: np.ndarray, scale: np.ndarray):
    """``compare`` for arrays of finite numbers: (agree mask, abs errors, rel errors)."""
    diff = np.abs(cached - recomputed)
    magnitude = np.maximum(np.maximum(np.abs(cached), np.abs(recomputed)), scale)
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = np.where(magnitude > 0, diff / magnitude, 0.0)
    agree = diff <= _allowance(cached, magnitude)
    return agree, diff, rel
