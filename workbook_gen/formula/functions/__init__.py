"""Excel's worksheet functions, by family, in one registry.

    from workbook_gen.formula import functions as fx
    fx.REGISTRY["VLOOKUP"]          # Function(name, family, fn, min_args, max_args, kinds, ...)
    fx.call("ROUND", [2.675, 2.0])  # 2.68
    fx.SUPPORTED                    # every registered name

Families: :mod:`.math`, :mod:`.logical`, :mod:`.lookup`, :mod:`.stats`, :mod:`.text`,
:mod:`.info`, :mod:`.date`, :mod:`.finance`, :mod:`.eng`. Coercion rules live in
:mod:`.coerce`; the table and the calling convention in :mod:`.registry`; LibreOffice's
deviations in :mod:`.dialect`. Nothing raises on bad data: Excel errors are returned
and propagate.
"""

from __future__ import annotations

from workbook_gen.formula.functions import (  # noqa: F401  (each module registers its family)
    date, eng, finance, info, logical, lookup, math, reference, statfit, stats, text,
    distributions, discrete, stattests, workdays, complex, engineering, database, matrix,
    regress, depreciation, bessel, textbytes, subtotal,
    lambdas, dynamic, arrayops, regex,  # (helper corpb: LAMBDA, dynamic arrays, regex)
    bonds, oddbonds,  # (helper corpb3: securities, day-count bases in daycount.py)
    weeks, spill, randarray, xlookup,
    cube, rtd,  # (answered from the caches the file keeps: OLAP, real-time data)
)
from workbook_gen.formula.functions.dialect import (
    LIBREOFFICE_DIFFERENCES, Difference, dialect_of, libreoffice_error, libreoffice_result,
    numeric_deviation,
)
from workbook_gen.formula.functions.calling import call
from workbook_gen.formula.functions.math import power
from workbook_gen.formula.functions.registry import (
    REGISTRY, Context, Function, RowDependent, Unanswered, register,
)
from workbook_gen.formula.functions import registry as _registry
from workbook_gen.xlerror import ExcelError

SUPPORTED = frozenset(REGISTRY)
VOLATILE = frozenset(n for n, f in REGISTRY.items() if f.volatile)
LAZY = frozenset(n for n, f in REGISTRY.items() if f.lazy)
# functions whose value is read from a cache the file keeps of something outside it
CACHED_OUTSIDE = cube.FUNCTIONS | rtd.FUNCTIONS

__all__ = ["REGISTRY", "SUPPORTED", "VOLATILE", "LAZY", "Context", "Function", "RowDependent",
           "Unanswered",
           "register",
           "call", "power", "LIBREOFFICE_DIFFERENCES", "Difference", "dialect_of", "libreoffice_result",
           "ExcelError"]
