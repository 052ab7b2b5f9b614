"""Calling a registered function with a dialect's semantics: ``call(name, args, ctx)``.

LibreOffice's numeric deviations and its own errors are applied here, around the
registry's call (the package face re-exports this ``call``)."""

from __future__ import annotations

from workbook_gen.formula.functions import registry as _registry
from workbook_gen.formula.functions.dialect import libreoffice_error, numeric_deviation
from workbook_gen.formula.functions.registry import Context


def call(name: str, args: list, ctx: Context | str | None = None):
    """Apply the registered function ``name`` to evaluated arguments (thunks for a lazy
    function). ``ctx`` is a :class:`Context` or a dialect name."""
    if not isinstance(ctx, Context):
        ctx = Context(dialect=ctx or "excel")
    if ctx.dialect == "libreoffice":
        deviation = numeric_deviation(name, args)
        if deviation is not None:
            return deviation
        return libreoffice_error(name, _registry.call(name, args, ctx), args)
    return _registry.call(name, args, ctx)
