"""Structure findings: names Excel would refuse, names that do not parse, references that
do not resolve, external links, cycles, unsupported and volatile functions.

A finding is reported and never fails the audit on its own: only cells that disagree do.
The cells a finding keeps from being recomputed are listed in the report's ``not_checked``.
"""

from __future__ import annotations

import re
from collections import defaultdict
from dataclasses import dataclass

from ..formula import ast
from ..names import excel_name_problem
from ..xlsx.reader import MISSING_PART

_BUILT_IN = re.compile(r"_xlnm\.[A-Za-z_]+")


@dataclass(frozen=True)
class Finding:
    cell: str       # a cell "Table!B2", a defined name, or a part of the file
    kind: str       # snake_case: "illegal_name", "circular_reference", ...
    message: str


def check_structure(inputs, evaluation, cell_name) -> list[Finding]:
    book = inputs.book
    findings = []
    scoped = [(n, None) for n in book.defined_names] + [
        (n, s.name) for s in book.sheets for n in s.defined_names]
    for name, sheet in scoped:
        problem = None if _BUILT_IN.fullmatch(name) else excel_name_problem(name)
        if problem:
            findings.append(Finding(name if sheet is None else f"{sheet}!{name}",
                                    "illegal_name", problem))
    for name, message in sorted(evaluation.bad_names.items()):
        findings.append(Finding(name, "defined_name_syntax",
                                f"the defined name does not parse, so the cells that use it "
                                f"are not checked: {message}"))
    for name, kind in book.other_sheets:
        if kind == MISSING_PART:
            findings.append(Finding(name, "unreadable_sheet",
                                    f"the workbook lists sheet {name!r} without its part "
                                    "(no relationship): its cells cannot be read, and the "
                                    "cells that read it are not checked"))
    for link in book.external_links:
        findings.append(Finding(link.part, "external_link",
                                f"the workbook links to {link.target}"))
    iterate = book.iterate
    for cycle in evaluation.cycles:
        path = " -> ".join(cell_name(k) for k in cycle[:8])
        more = f" (and {len(cycle) - 8} more)" if len(cycle) > 8 else ""
        findings.append(Finding(cell_name(cycle[0]), "circular_reference",
                                f"{len(cycle)} cells refer to each other: {path}{more}; "
                                + ("they and what reads them are not checked (iterative "
                                   "calculation is on)" if iterate else
                                   "with iterative calculation off they show 0 (LibreOffice: "
                                   "Err:522), as does what takes its value from them")))
    unknown = evaluation.unknown
    findings += _by_function({k: v for k, v in evaluation.unsupported.items()
                              if k not in unknown}, "unsupported_function",
                             "{n} cells call {f}, which the evaluator lacks; they and their "
                             "dependents are not checked", cell_name)
    findings += _by_function({k: v for k, v in evaluation.unsupported.items() if k in unknown},
                             "unsupported_function",
                             "{n} cells call {f}, a name Excel does not know as a function "
                             "here (an add-in's or a macro's, or one newer than Excel 2007 "
                             "stored without its _xlfn. prefix): #NAME? unless an add-in or "
                             "a macro defines it", cell_name)
    findings += _by_function(evaluation.volatile, "volatile_function",
                             "{n} cells call {f}, a volatile function", cell_name)
    findings.extend(_unresolved(inputs, evaluation, cell_name))
    return findings


def _by_function(cells: dict, kind: str, text: str, cell_name) -> list[Finding]:
    """One finding per function: its first cell and how many cells call it."""
    first: dict[str, tuple] = {}
    count: dict[str, int] = defaultdict(int)
    for key in sorted(cells):
        for f in cells[key]:
            first.setdefault(f, key)
            count[f] += 1
    return [Finding(cell_name(first[f]), kind, text.format(n=count[f], f=f))
            for f in sorted(first)]


def _unresolved(inputs, evaluation, cell_name) -> list[Finding]:
    """Names and sheets a formula refers to that the workbook does not have.

    One tree per run of formulas equal in R1C1 form (the evaluator parsed each run
    once): names and sheet names do not change along a filled column."""
    book = inputs.book
    sheets = {s.upper() for s in book.sheet_names}
    names = {n.upper() for n in book.defined_names}
    local = {(s.name, n.upper()) for s in book.sheets for n in s.defined_names}
    local_any = {n for _, n in local}
    findings = []
    for run in evaluation.runs:
        key = (run.sheet, run.first, run.col)
        for node in ast.walk(run.node):
            sheet = getattr(node, "sheet", None)
            if sheet and sheet.upper() not in sheets and not sheet.startswith("["):
                findings.append(Finding(cell_name(key), "unresolved_reference",
                                        f"no sheet named {sheet!r}"))
            if isinstance(node, ast.Name):
                upper = node.name.upper()
                if upper.startswith(("_XLPM.", "_XLETA.")):  # a LAMBDA's parameter, a function
                    continue
                known = (upper in local_any if node.sheet else
                         upper in names or (run.sheet, upper) in local)
                if not known:
                    findings.append(Finding(cell_name(key), "unresolved_reference",
                                            f"no defined name {node.name!r}"))
    return findings
