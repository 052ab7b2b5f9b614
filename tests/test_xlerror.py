"""workbook_gen/xlerror.py: the error values are exactly Excel's, spelled as Excel stores
them (openpyxl's list of the cell errors, the OOXML spec's ST_CellError), read back from
text case-insensitively; the codes used in numpy error masks are small, unique, non-zero
and stable; the evaluator's own CIRC mark is never read from a file."""

from __future__ import annotations

from openpyxl.cell.cell import ERROR_CODES

from workbook_gen.xlerror import ExcelError


def test_the_classic_errors_are_openpyxls():
    # ST_CellError (ECMA-376 part 1, 18.18.11): #NULL! #DIV/0! #VALUE! #REF! #NAME? #NUM! #N/A
    # (openpyxl adds #GETTING_DATA, which Excel writes while a data type loads)
    for text in ERROR_CODES:
        assert ExcelError.from_text(text).value == text
    classic = [e.value for e in ExcelError][:7]
    assert classic == ["#NULL!", "#DIV/0!", "#VALUE!", "#REF!", "#NAME?", "#NUM!", "#N/A"]


def test_codes_follow_error_type_for_the_classic_seven():
    # ERROR.TYPE gives 1..7 for these seven in this order (Microsoft's ERROR.TYPE page)
    assert [ExcelError.from_text(t).code for t in
            ("#NULL!", "#DIV/0!", "#VALUE!", "#REF!", "#NAME?", "#NUM!", "#N/A")] == \
        [1, 2, 3, 4, 5, 6, 7]
    codes = [e.code for e in ExcelError]
    assert len(set(codes)) == len(codes) and min(codes) == 1 and max(codes) < 256  # uint8
    for e in ExcelError:
        assert ExcelError.from_code(e.code) is e


def test_text_reads_case_insensitively_and_strips():
    assert ExcelError.from_text(" #div/0! ") is ExcelError.DIV0
    assert ExcelError.from_text("#n/a") is ExcelError.NA
    assert ExcelError.from_text("#SPILL!") is ExcelError.SPILL
    assert ExcelError.from_text("DIV/0") is None
    assert ExcelError.from_text("") is None
    assert ExcelError.from_text("#CIRCULAR") is None   # the evaluator's mark, not Excel's
    assert str(ExcelError.REF) == "#REF!"
