"""RTD answered from the real-time data the file keeps (:mod:`workbook_gen.xlsx.topics`).

RTD(ProgID, server, topic1, [topic2], ...) asks a COM server for live data; the file
keeps the last value each call (ProgID, and the server and topics as text) received.
That value is the call's; a call whose parameters the file does not hold raises
:class:`Unanswered` (the cell is "not checked"), never a guess.
"""

from __future__ import annotations

from workbook_gen.formula.functions.registry import Unanswered, register
from workbook_gen.formula.values import to_text
from workbook_gen.xlerror import ExcelError

FUNCTIONS = frozenset({"RTD"})


@register("RTD", 3, 30, omitted=True)  # (an omitted server is "")
def _rtd(ctx, progid, server, *topics):
    args = [progid, server, *topics]
    error = next((a for a in args if isinstance(a, ExcelError)), None)
    if error is not None:
        return error
    texts = ["" if a is None else to_text(a) for a in args]
    if any(isinstance(t, ExcelError) for t in texts):
        return next(t for t in texts if isinstance(t, ExcelError))
    calls = ctx.workbook.topics(texts[0])
    key = tuple(texts[1:])
    if calls is None or key not in calls:
        raise Unanswered("RTD: the call is not in the file's real-time data cache: "
                         + ", ".join(repr(t) for t in texts))
    return calls[key]
