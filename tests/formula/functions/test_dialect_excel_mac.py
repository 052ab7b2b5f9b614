"""Excel's rules where LibreOffice's differ, on the cells of the corpus's
formulas__test.xlsx (saved by Mac Excel 16): each cell below must be recomputed and agree
with Excel's cached value. (The LibreOffice side of each rule is in
formula/functions/test_registry_libreoffice.py, against LibreOffice itself.)"""

from __future__ import annotations

import pytest

CORPUS = "formulas__test.xlsx"
CELLS = {
    # SUMPRODUCT of arrays of different sizes: an error in them before #VALUE!
    "'MATH & TRIG'!AE75": "SUMPRODUCT(P75:Q75,H75:I75,I75:K75) = #NUM!",
    "'MATH & TRIG'!AF75": "SUMPRODUCT(Q75:R75,I75:K75,K75:L75) = #REF!",
    # PROB: an empty cell as upper_limit is 0
    "STATISTICAL!Z86": "PROB({1,2,3,4,5},{0.1,0.2,0.3,0.3,0.1},1,H86) = 0",
    # INDEX: an error as area_num is the result
    "LOOKUP!AB54": "INDEX({2,3,4,5},1,1,N54) (#NAME?) = #NAME?",
    # IRR: an error among the cash flows is #VALUE!
    "FINANCIAL!Z26": "IRR({-7,2,-1,4,-3;7,2,-1,4,#N/A}) = #VALUE!",
    "FINANCIAL!AB26": "IRR({...,#DIV/0!}) = #VALUE!",
    "FINANCIAL!AF26": "IRR({...,#REF!}) = #VALUE!",
    "FINANCIAL!Z27": "IRR(C27:K27), #N/A in the range = #VALUE!",
    # XIRR, XNPV: the guess's error, then the dates', then the values'; a boolean guess,
    # rate or cash flow #VALUE!; pairs of empty cells and pairs with text left out
    "FINANCIAL!S54": "XIRR(C56,$C$55:$G$55,$C$54:$G$54): the guess range's #VALUE!",
    "FINANCIAL!U54": "XIRR({-10,#N/A,1,2,7},{3,#REF!,7,4,9}) = #REF!",
    "FINANCIAL!V54": "XIRR({-10,#N/A,1,2,7},{3,#VALUE!,7,4,9},#REF!) = #REF!",
    "FINANCIAL!Y54": "XIRR($C$55:$G$55,$C$54:$G$54,TRUE) = #VALUE!",
    "FINANCIAL!Y55": "XIRR($C$55:$G$55,$C$54:$G$54,J56) (TRUE) = #VALUE!",
    "FINANCIAL!Z56": "XNPV(J56,$C$55:$G$55,$C$54:$G$54) (TRUE) = #VALUE!",
    "FINANCIAL!AD54": "XIRR($C$55:H$55,$C$54:H$54), H empty = 0.59931975",
    "FINANCIAL!AE54": "XIRR($C$55:I$55,$C$54:I$54), I55 text = 0.59931975",
    "FINANCIAL!AF54": "XIRR($C$55:J$55,$C$54:J$54), J55 TRUE = #VALUE!",
    # an Analysis ToolPak function takes no boolean: #VALUE!
    "'MATH & TRIG'!Y31": "FACTDOUBLE(TRUE)",
    "'MATH & TRIG'!Y45": "MROUND(TRUE,0)",
    "'MATH & TRIG'!Y70": "SQRTPI(TRUE)",
    "FINANCIAL!Y13": "CUMIPMT(TRUE,5.5,125000,3,5,1)",
    # FACTDOUBLE: -1 is the empty product, below -1 #NUM!
    "'MATH & TRIG'!V31": "FACTDOUBLE(-1) = 1",
    "'MATH & TRIG'!T31": "FACTDOUBLE(-1.1) = #NUM!",
    # ARABIC read from the right, subtracting a numeral below the largest seen
    "'MATH & TRIG'!T9": 'ARABIC("IIIIIIV") = -1',
    "'MATH & TRIG'!V9": 'ARABIC("IILmIIC") = 1046',
    "'MATH & TRIG'!AJ9": "the same in an array formula",
    # ADDRESS with an empty sheet name writes its "!"
    "LOOKUP!S3": 'ADDRESS(1.1,3,4,4.1,<empty cell>) = "!C1"',
    "LOOKUP!AI3": "the same in an array formula",
    # IMSUM and IMPRODUCT of "i" and "j" numbers: #VALUE! (IMSUB: #NUM!)
    "ENGINEERING!S52": "IMSUM(D52:E52,F52)",
    "ENGINEERING!T44": "IMPRODUCT(F44,E44)",
    "ENGINEERING!T51": "IMSUB(E51,F51) = #NUM!",
    # AND/OR/XOR: a text argument's #VALUE! gives way to a later error value
    "LOGICAL!AP3": 'AND(TRUE,"0",#REF!) = #REF!',
    "LOGICAL!AS3": 'AND(TRUE,"ciao",#REF!,"0") = #REF!',
    "LOGICAL!AP21": 'OR(TRUE,"0",#REF!) = #REF!',
    "LOGICAL!AP27": 'XOR(TRUE,"0",#REF!) = #REF!',
    # ROW and COLUMN of an empty intersection: its #NULL!
    "LOOKUP!AG13": "COLUMN(C12:E13 F12:H13) = #NULL!",
    "LOOKUP!AG113": "ROW(C112:E113 F112:H113) = #NULL!",
    # a union's size is #REF!; an intersection with a union intersects each area; AREAS
    "LOOKUP!S15": "COLUMNS((D15:G15,I15:J15,K15:N15)) = #REF!",
    "LOOKUP!S115": "ROWS((D115:G115,I114:J115,K115:N115)) = #REF!",
    "LOOKUP!V15": "COLUMNS(((F15:G15,G15:I15,F19:G19,G19:I19) G14:G44)) = #REF! (4 areas)",
    "LOOKUP!V115": "ROWS(((F115:G115,G115:I115,F118:G118,G118:I118) G114:G134)) = #REF!",
    "CORE!E7": "SUM(E3:G4 (B2:E5,G2:H5)) = 16",
    "LOOKUP!R4": "AREAS(C4:F4) = 1",
    "LOOKUP!S4": "AREAS((D4:G4,I4:J4,K4:N4)) = 3",
    "LOOKUP!T4": "AREAS((E4:H4 J4:K4 L4:O4)) = #NULL! (two intersections in a row)",
    "LOOKUP!V4": "AREAS(((F4:G4,G4:I4,F6:G6,G6:I6) G3:G11)) = 4",
    # ISFORMULA: the cell's formula, each cell's for a range in an array formula
    "INFORMATION!R10": "ISFORMULA(C10) = FALSE",
    "INFORMATION!U10": "ISFORMULA(F10) = TRUE",
    "INFORMATION!AK10": "{=ISFORMULA(C10:J10)}, F10's = TRUE",
    "INFORMATION!AP10": "{=ISFORMULA(C10:J10)} beyond the range = #N/A",
    "EXTRA!BG77": "{=ISFORMULA(BC75:BD93)} = TRUE",
    # tests and fits of two arrays pass over a #NULL! that another error follows; CHISQ.TEST
    # takes the actual values' errors first, and #DIV/0! without a pair of numbers; a paired
    # T.TEST takes its errors pair by pair
    "STATISTICAL!AD26": "COVARIANCE.P({#NULL!,#NUM!,#REF!},{#REF!,-0.01,-0.01}) = #NUM!",
    "STATISTICAL!AD55": "INTERCEPT({#NULL!,#NUM!,..},{#VALUE!,..}) = #NUM!",
    "STATISTICAL!AD77": "PEARSON({#NULL!,#NUM!},{#REF!,#DIV/0!}) = #NUM!",
    "STATISTICAL!AD34": "F.TEST({#NULL!,#NUM!},{#REF!,#DIV/0!}) = #NUM!",
    "STATISTICAL!AD17": "CHISQ.TEST({#NULL!,#NUM!},{#REF!,x}) = #NUM!",
    "STATISTICAL!Y17": "CHISQ.TEST({TRUE,#VALUE!},{#N/A,#DIV/0!}) = #VALUE!",
    "STATISTICAL!V17": "CHISQ.TEST({4,,text},{,text,TRUE}) = #DIV/0!",
    "STATISTICAL!AD107": "{=T.TEST({#NULL!,#NUM!},{#REF!,x},1,1)} = #NUM!",
    "STATISTICAL!Y107": "{=T.TEST({TRUE,#VALUE!},{#N/A,#DIV/0!},1,1)} = #N/A",
    "STATISTICAL!AD108": "{=T.TEST({#NULL!,#NUM!},{#REF!,x},2,2)} = #NUM!",
    # LINEST, LOGEST, TREND, GROWTH: an error among the values or the flags is #VALUE!
    "STATISTICAL!Z58": "{=LINEST(C58:E58,E58:G58,#N/A,0)} = #VALUE!",
    "STATISTICAL!AB58": "{=LINEST({#N/A,#DIV/0!,#NAME?},{..},0,0)} = #VALUE!",
    "STATISTICAL!AC59": "{=LOGEST({#DIV/0!,..},{..},0,0)} = #VALUE!",
    "STATISTICAL!AA51": "{=GROWTH(..,..,{#N/A,..})} = #VALUE!",
    "STATISTICAL!AB113": "{=TREND(..,..,{#DIV/0!,..})} = #VALUE!",
    # MODE.SNGL, MODE.MULT: a direct "" left out, an omitted argument #VALUE!
    "STATISTICAL!S71": 'MODE.SNGL(D71:E71,E71:F71,F71:G71,"") = 0.2',
    "STATISTICAL!S69": '{=MODE.MULT(D69:E69,E69:F69,F69:G69,"")} = 0.1',
    "STATISTICAL!AG69": "{=MODE.MULT(H69:J69,D69:I69,E69:G69,F69:H69,)} = #VALUE!",
    # INDEX of a union: area_num picks the area, #REF! beyond
    "LOOKUP!AQ52": "{=INDEX((C52:C54,D52:D54),1,1,{3;2;1})}, area 3 = #REF!",
    "LOOKUP!AQ53": "the same, area 2 = D52",
    "LOOKUP!AS53": "{=INDEX((C52:C54,D52:D54),{3;2;1},1,{3;2;1})}, row 2 of area 2 = D53",
    "LOOKUP!AT52": "{=INDEX((C52:C53,D52:D53),1,1,{3;2})} = #REF!",
    # an IS function over a range in a wider array formula: f(#N/A) beyond the range
    "INFORMATION!AW7": "{=ISERR(C7:Q7)} beyond Q = FALSE",
    "INFORMATION!AW12": "{=ISNA(C12:Q12)} beyond Q = TRUE",
    # TYPE of a function as a value
    "INFORMATION!S24": "TYPE(_xleta.SUM) = 128",
    # Student's t far tails from the tail itself, and the density at 0 degrees of freedom
    "STATISTICAL!X103": "T.DIST.2T(60,60) = 2.85e-55",
    "STATISTICAL!X104": "T.DIST.RT(60,60) = 1.42e-55",
    "STATISTICAL!R102": "T.DIST(0,0,FALSE) = #DIV/0!",
    # Z.TEST: x's error, then sigma's, before the array's; sigma 0 #NUM!; one number #DIV/0!
    "STATISTICAL!U121": "Z.TEST({3.2,0.7},2,0) = #NUM!",
    "STATISTICAL!V121": "Z.TEST({4,,text},0,2) = #DIV/0!",
    "STATISTICAL!Y121": "Z.TEST({TRUE,#VALUE!},#N/A) = #N/A",
    "STATISTICAL!AB121": "Z.TEST({#DIV/0!,#NAME?},3,#NAME?) = #NAME?",
    "STATISTICAL!AE121": "Z.TEST({#NUM!,#REF!},x) = #NUM!",
    # HYPGEOM.DIST: zeros allowed; the cumulative form is 0 below the support, 1 above
    "STATISTICAL!R54": "HYPGEOM.DIST(0,0,0,0,FALSE) = 1",
    "STATISTICAL!W54": "HYPGEOM.DIST(0,0,4,4,TRUE) = 1",
    "STATISTICAL!AG54": "HYPGEOM.DIST(0,2,3,3,TRUE) = 0",
    "STATISTICAL!AI54": "HYPGEOM.DIST(5,3,2,30,TRUE) = 1",
    "STATISTICAL!S54": "HYPGEOM.DIST(5,10,30,7,FALSE) = #NUM!",
    # NUMBERVALUE: parentheses, percent signs inside and after them, separators
    "TEXT!R27": 'NUMBERVALUE("(2.500,27)",",",".") = -2500.27',
    "TEXT!S27": 'NUMBERVALUE("(2,500.27)",",",".") = #VALUE! (group after decimal)',
    "TEXT!U27": 'NUMBERVALUE("(2,500.27%)%",".",",.,") = -0.250027',
    "TEXT!V27": 'NUMBERVALUE("(,25,,0,0.27E + 6%)%",".",",.,") = -250027',
    "TEXT!W28": 'NUMBERVALUE("(2500,27E+6%)%",",") = -250027',
    "TEXT!V28": 'NUMBERVALUE("(2,500.27%)%",",") = #VALUE!',
    "TEXT!AB28": 'NUMBERVALUE("1",<empty cell>) = #VALUE!',
    "TEXT!R28": 'NUMBERVALUE("(-2500.27E+2%)%",".",",.,") = #VALUE!',
    # LARGE and SMALL: k below 1 #NUM!; LARGE rounds a fractional k up, SMALL truncates
    "STATISTICAL!AJ57": "LARGE({0.1,-10,0.9,2.2,-0.1},0.9) = #NUM!",
    "STATISTICAL!AK57": "LARGE({0.1,-10,0.9,2.2,-0.1},2.2) = 0.1",
    "STATISTICAL!AJ95": "SMALL({0,-10,0.9,2.2,-0.1},0.9) = #NUM!",
    "STATISTICAL!AK95": "SMALL({0,-10,0.9,2.2,-0.1},2.2) = -0.1",
    # FREQUENCY with bins of empty cells: one bin at 0
    "STATISTICAL!W43": "FREQUENCY({1,2,3,0,-1},<empty cell>) = {2;3}",
    "EXTRA!J50": "FREQUENCY({2;3;4;},<4 empty cells>) = {0;3}",
}


@pytest.fixture(scope="module")
def report(corpus_audits):
    return corpus_audits[CORPUS].report


@pytest.mark.parametrize("cell", list(CELLS), ids=list(CELLS.values()))
def test_cell_agrees_with_mac_excel(report, cell):
    assert cell not in report.not_checked
    assert cell not in {m.cell for m in report.mismatches}


@pytest.mark.parametrize("x, df", [(60.0, 60.0), (40.0, 3.0), (9.0, 200.0), (1e3, 1.0)])
def test_t_tails_agree_with_the_integrated_density(x, df):
    """T.DIST.RT and T.DIST.2T against mpmath's quadrature of Student's density from x to
    infinity at 50 digits (an independent path: no incomplete beta function)."""
    import mpmath

    from workbook_gen.formula import DictResolver, evaluate, parse
    with mpmath.workdps(50):
        x_, n = mpmath.mpf(x), mpmath.mpf(df)
        norm = mpmath.gamma((n + 1) / 2) / (mpmath.sqrt(n * mpmath.pi) * mpmath.gamma(n / 2))
        step = (x_ * x_ + n) / ((n + 1) * x_)  # the density's decay length at x
        points = [x_ + step * (2 ** (k / 2) - 1) for k in range(120)] + [mpmath.inf]
        tail = float(mpmath.quad(lambda t: norm * (1 + t * t / n) ** (-(n + 1) / 2), points))
    for formula, expected in ((f"T.DIST.RT({x},{df})", tail), (f"T.DIST.2T({x},{df})", 2 * tail)):
        got = evaluate(parse("=_xlfn." + formula), DictResolver({}), dialect="excel")
        assert got == pytest.approx(expected, rel=1e-9, abs=0), formula  # quad: ~3e-12
