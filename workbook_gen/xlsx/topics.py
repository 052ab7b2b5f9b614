"""The real-time data a workbook keeps for its RTD calls (xl/volatileDependencies.xml).

ECMA-376 Part 1, 18.17 (``volTypes/volType type="realTimeData"/main first/tp``):
each ``main`` groups the calls to one RTD server (``first``: its ProgID); each ``tp``
is one set of parameter values (``stp``: the server and the topics, in the call's order)
with the last value the server returned for it (``v``, of type ``t``: n, s, b, e) and
the cells that call it ([MS-XLSB] 2.2.13: "The last value returned by the call that
corresponds to the volatile dependency").
"""

from __future__ import annotations

from xml.etree.ElementTree import Element

from workbook_gen.xlerror import ExcelError

Topics = dict[str, dict[tuple[str, ...], object]]  # ProgID (case-folded) -> strings -> value


def _local(el: Element) -> str:
    return el.tag.rpartition("}")[2]


def _value(kind: str, text: str | None):
    if text is None:
        return None
    if kind == "s":
        return text
    if kind == "b":
        return text in ("1", "true")
    if kind == "e":
        return ExcelError.from_text(text)
    try:
        return float(text)
    except ValueError:
        return None


def read_topics(pkg, rels: dict) -> Topics:
    """{ProgID: {(server, topic1, ...): value}} of the RTD calls the file caches."""
    part = next((p for k, p in rels.values() if k == "volatileDependencies" and p
                 and not p.startswith("external:")), None)
    out: Topics = {}
    if part is None:
        return out
    for vol_type in pkg.parse(part):
        if _local(vol_type) != "volType" or vol_type.get("type") != "realTimeData":
            continue
        for main in vol_type:
            if _local(main) != "main" or main.get("first") is None:
                continue
            topics = out.setdefault(main.get("first", "").casefold(), {})
            for tp in main:
                if _local(tp) != "tp":
                    continue
                strings = tuple(s.text or "" for s in tp if _local(s) == "stp")
                v = next((c.text for c in tp if _local(c) == "v"), None)
                value = _value(tp.get("t", "n"), v)
                if value is not None:
                    topics[strings] = value
    return out
