"""Structure checks: legal names, references that resolve, only supported functions,
no external links; volatile functions are reported."""

from __future__ import annotations

from dataclasses import dataclass

from ..formula import ast
from ..names import name_problem



@dataclass(frozen=True)
class Finding:
    kind: str       # "illegal name", "unresolved reference", "unsupported function", ...
    where: str      # a cell "Table!B2", a name, or a part of the file
    detail: str
    blocking: bool = True  # False: reported, does not fail the audit


def check_structure(inputs, evaluation, cell_name) -> list[Finding]:
    book = inputs.book
    findings = []
    for name in book.defined_names:
        problem = name_problem(name)
        if problem:
            findings.append(Finding("illegal name", name, problem))
    for link in book.external_links:
        findings.append(Finding("external link", str(getattr(link, "part", link)),
                                f"the workbook links to {getattr(link, 'target', link)}"))
    for key, functions in evaluation.unsupported.items():
        findings.append(Finding("unsupported function", cell_name(key), ", ".join(functions)))
    for key, functions in evaluation.volatile.items():
        findings.append(Finding("volatile function", cell_name(key), ", ".join(functions),
                                blocking=False))
    for key in evaluation.external:
        findings.append(Finding("external reference", cell_name(key), inputs.formulas[key]))
    for key, message in {**evaluation.syntax_errors, **inputs.broken}.items():
        findings.append(Finding("formula syntax", cell_name(key), message))
    for key in inputs.array_cells:
        if book.sheet(key[0]).cell(key[1], key[2]).is_array:
            findings.append(Finding("array formula", cell_name(key),
                                    "array formulas are not recomputed", blocking=False))
    findings.extend(_unresolved(inputs, evaluation, cell_name))
    return findings


def _unresolved(inputs, evaluation, cell_name) -> list[Finding]:
    """Names and sheets a formula refers to that the workbook does not have.

    One tree per run of formulas equal in R1C1 form (the evaluator parsed each run
    once): names and sheet names do not change along a filled column."""
    book = inputs.book
    sheets = {s.upper() for s in book.sheet_names}
    names = {n.upper() for n in book.defined_names}
    local = {(s.name, n.upper()) for s in book.sheets for n in s.defined_names}
    findings = []
    for run in evaluation.runs:
        key = (run.sheet, run.first, run.col)
        for node in ast.walk(run.node):
            sheet = getattr(node, "sheet", None)
            if sheet and sheet.upper() not in sheets and not sheet.startswith("["):
                findings.append(Finding("unresolved reference", cell_name(key),
                                        f"no sheet named {sheet!r}"))
            if isinstance(node, ast.Name) and node.name.upper() not in names \
                    and (run.sheet, node.name.upper()) not in local:
                findings.append(Finding("unresolved reference", cell_name(key),
                                        f"no defined name {node.name!r}"))
    return findings
