"""LibreOffice's semantics beside Excel's, in an audit: re-evaluating a cell in
LibreOffice's dialect (``libreoffice_explains``), and the comparison of an Excel-saved
file with LibreOffice's recalculation (``against_libreoffice``), where a cell LibreOffice
computes by its own rules (SLOPE of two areas of different sizes: #VALUE! there, #N/A in
Excel) is LibreOffice's difference, not the file's failure."""

from __future__ import annotations

import time

import numpy as np

from ..errors import FormulaSyntaxError
from ..formula import parse
from ..formula.functions import Unanswered as fx_unanswered
from ..formula.scalar import evaluate as evaluate_scalar
from .compare import compare
from .inputs import AuditInputs
from .recomputed import RecomputedResolver
from .report import EngineResult, Mismatch


def libreoffice_explains(inputs: AuditInputs, key, value_of, cached) -> bool:
    """Does LibreOffice's evaluation of this cell (its known deviations from Excel:
    SQRT(-1), ATAN2(0,0), 0^0, odd roots) give the cached value?"""
    try:
        node = parse(inputs.text_of(key).removeprefix("{=").removesuffix("}"))
    except FormulaSyntaxError:
        return False
    resolver = RecomputedResolver(value_of, inputs.book.defined_names, key[0], inputs.is_formula)
    try:
        with np.errstate(all="ignore"):  # overflow is #NUM! there too (engine._floats_quiet)
            value = evaluate_scalar(node, resolver, dialect="libreoffice")
    except (ArithmeticError, ValueError, TypeError, IndexError, KeyError, RecursionError,
            fx_unanswered):
        return False  # the re-check is a courtesy: a defect in it must not lose the file
    return compare(cached, value, 0.0).agree

def against_libreoffice(inputs: AuditInputs, theirs: dict, local, value_of, scales, skip,
                        started: float, name_of) -> EngineResult:
    """Every formula cell LibreOffice recalculated (``theirs``: sheet -> {ref: value})
    against ours: an aggregate against what it makes of LibreOffice's own range
    (``local``, in LibreOffice's dialect), another cell against our value.

    A cell is LibreOffice's difference (``EngineResult.differences``) where LibreOffice's
    value is what our evaluator gives in LibreOffice's dialect from the same precedents,
    while the file's cached value is our Excel result; otherwise a value LibreOffice
    computes apart from ours is a mismatch."""
    mismatches, differences, cells = [], [], 0
    for key, formula in inputs.formulas.items():
        if key in skip:
            continue
        ref = inputs.ref(key)
        if ref not in theirs.get(key[0], {}):
            continue
        cells += 1
        value, excel = theirs[key[0]][ref], value_of(*key)
        excel_scale = scales.get(key, 0.0)
        if key in local.values:  # an aggregate: what it makes of LibreOffice's own range
            ours, scale = local.values[key], local.operands_scale[key]
        else:
            ours, scale = excel, excel_scale
        agree = compare(value, ours, scale).agree
        if agree and (ours is excel or compare(value, excel, excel_scale).agree):
            continue
        dialect = (libreoffice_explains(inputs, key, value_of, value)
                   and compare(inputs.cached.get(key), excel, excel_scale).agree)
        if dialect:  # (LibreOffice's and Excel's rules differ on these very precedents)
            differences.append(Mismatch(name_of(key), formula, value, excel))
        elif not agree:
            mismatches.append(Mismatch(name_of(key), formula, value, ours))
    return EngineResult("libreoffice", cells, mismatches, len(differences),
                        time.perf_counter() - started, differences)
