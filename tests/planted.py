"""Small workbooks written with XlsxWriter holding formulas and the cached values a test
chooses (a planted disagreement among them), for the auditor's module tests."""

from __future__ import annotations

import xlsxwriter


def planted_book(path):
    """S: A1=2, A2=3, A3 text; B1 =A1*3 (6), B2 =A2*3 (9), B3 =A1+A2 cached 99 (wrong:
    5); C1:C2 {=A1:A2*2} (4, 6); D1 =k*10 (20), k = S!$A$1. T: B1 =S!B1+1 (7)."""
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("S")
    s.write_number("A1", 2)
    s.write_number("A2", 3)
    s.write_string("A3", "txt")
    s.write_formula("B1", "=A1*3", None, 6)
    s.write_formula("B2", "=A2*3", None, 9)
    s.write_formula("B3", "=A1+A2", None, 99)
    s.write_array_formula("C1:C2", "{=A1:A2*2}", None, 4)
    s.write_number("C2", 6)  # the array's second cell: its cached value
    book.define_name("k", "=S!$A$1")
    s.write_formula("D1", "=k*10", None, 20)
    t = book.add_worksheet("T")
    t.write_formula("B1", "=S!B1+1", None, 7)
    book.close()
    return path
