"""Excel's worksheet functions, by family, in one registry.

    from workbook_gen.formula import functions as fx
    fx.REGISTRY["VLOOKUP"]          # Function(name, family, fn, min_args, max_args, kinds, ...)
    fx.call("ROUND", [2.675, 2.0])  # 2.68
    fx.SUPPORTED                    # every registered name

Families, one package each, after Excel's categories: :mod:`.math`, :mod:`.statistical`,
:mod:`.engineering`, :mod:`.financial`, :mod:`.date`, :mod:`.text`, :mod:`.logical`,
:mod:`.lookup`, :mod:`.information`, :mod:`.database`, :mod:`.cube`. A function's family is
the package that registers it (:func:`.registry.family_of`), never written by hand; the
modules beside the packages register nothing. Coercion rules live in :mod:`.coerce`; the
table and the calling convention in :mod:`.registry`; LibreOffice's deviations in
:mod:`.dialect`; the library's own description (docs/functions.md) in :mod:`.catalog`.
Nothing raises on bad data: Excel errors are returned and propagate.
"""

from __future__ import annotations

from workbook_gen.formula.functions import (  # noqa: F401  (each family registers itself)
    math, statistical, engineering, financial, date, text, logical, lookup, information,
    database, cube,
)
from workbook_gen.formula.functions.dialect import (
    LIBREOFFICE_DIFFERENCES, Difference, dialect_of, libreoffice_error, libreoffice_result,
    numeric_deviation,
)
from workbook_gen.formula.functions.calling import call
from workbook_gen.formula.functions.math.core import power
from workbook_gen.formula.functions.registry import (
    REGISTRY, Context, Function, RowDependent, Unanswered, register,
)
from workbook_gen.formula.functions import registry as _registry
from workbook_gen.xlerror import ExcelError

SUPPORTED = frozenset(REGISTRY)
VOLATILE = frozenset(n for n, f in REGISTRY.items() if f.volatile)
LAZY = frozenset(n for n, f in REGISTRY.items() if f.lazy)
# functions whose value is read from a cache the file keeps of something outside it
CACHED_OUTSIDE = cube.core.FUNCTIONS | lookup.rtd.FUNCTIONS

__all__ = ["REGISTRY", "SUPPORTED", "VOLATILE", "LAZY", "Context", "Function", "RowDependent",
           "Unanswered",
           "register",
           "call", "power", "LIBREOFFICE_DIFFERENCES", "Difference", "dialect_of", "libreoffice_result",
           "ExcelError"]
