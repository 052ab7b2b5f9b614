"""Which function names Excel knows, and which it knows only with their ``_xlfn.`` prefix.

[MS-XLSX] section 2.2.2 (Formulas) lists the *future functions*: the functions added after
the file format was standardised (Excel 2010 on), which a file stores with the ``_xlfn.``
prefix (``_xlfn._xlws.`` for FILTER and SORT). Excel reads a future function's name
without its prefix as an unknown name: ``MINIFS(A1:A9,B1:B9,">0")`` written by a tool
that left the prefix out is ``#NAME?`` in Excel (LibreOffice computes it).

The functions of the standard itself (ECMA-376 Part 1, 18.17.7) need no prefix: those the
evaluator implements are its registry's names; :data:`STANDARD_UNIMPLEMENTED` lists the
others (tests check the union against openpyxl's list of the standard's functions).

A name that is neither, called as a function, is Excel's ``#NAME?`` unless an add-in or
the workbook's VBA project defines it: the audit cannot tell, so such a cell agrees only
where Excel cached ``#NAME?`` and is otherwise not checked (:mod:`evaluator.engine`).
"""

from __future__ import annotations

FUTURE = frozenset("""
ACOT ACOTH AGGREGATE ANCHORARRAY ARABIC ARRAYTOTEXT BASE BETA.DIST BETA.INV BINOM.DIST
BINOM.DIST.RANGE BINOM.INV BITAND BITLSHIFT BITOR BITRSHIFT BITXOR BYCOL BYROW CEILING.MATH
CEILING.PRECISE CHISQ.DIST CHISQ.DIST.RT CHISQ.INV CHISQ.INV.RT CHISQ.TEST CHOOSECOLS
CHOOSEROWS COMBINA CONCAT CONFIDENCE.NORM CONFIDENCE.T COT COTH COVARIANCE.P COVARIANCE.S
CSC CSCH DAYS DECIMAL DROP ENCODEURL ERF.PRECISE ERFC.PRECISE EXPAND EXPON.DIST F.DIST
F.DIST.RT F.INV F.INV.RT F.TEST FIELDVALUE FILTER FILTERXML FLOOR.MATH FLOOR.PRECISE
FORECAST.ETS FORECAST.ETS.CONFINT FORECAST.ETS.SEASONALITY FORECAST.ETS.STAT FORECAST.LINEAR
FORMULATEXT GAMMA GAMMA.DIST GAMMA.INV GAMMALN.PRECISE GAUSS GROUPBY HSTACK HYPGEOM.DIST IFNA
IFS IMAGE IMCOSH IMCOT IMCSC IMCSCH IMSEC IMSECH IMSINH IMTAN ISFORMULA ISOMITTED ISOWEEKNUM
LAMBDA LET LOGNORM.DIST LOGNORM.INV MAKEARRAY MAP MAXIFS MINIFS MODE.MULT MODE.SNGL MUNIT
NEGBINOM.DIST NORM.DIST NORM.INV NORM.S.DIST NORM.S.INV NUMBERVALUE PDURATION PERCENTILE.EXC
PERCENTILE.INC PERCENTOF PERCENTRANK.EXC PERCENTRANK.INC PERMUTATIONA PHI PIVOTBY
POISSON.DIST QUARTILE.EXC QUARTILE.INC QUERYSTRING RANDARRAY RANK.AVG RANK.EQ REDUCE
REGEXEXTRACT REGEXREPLACE REGEXTEST RRI SCAN SEC SECH SEQUENCE SHEET SHEETS SINGLE SKEW.P
SORT SORTBY STDEV.P STDEV.S STOCKHISTORY SWITCH T.DIST T.DIST.2T T.DIST.RT T.INV T.INV.2T
T.TEST TAKE TEXTAFTER TEXTBEFORE TEXTJOIN TEXTSPLIT TOCOL TOROW TRIMRANGE UNICHAR UNICODE
UNIQUE VALUETOTEXT VAR.P VAR.S VSTACK WEBSERVICE WEIBULL.DIST WRAPCOLS WRAPROWS XLOOKUP
XMATCH XOR Z.TEST
_TRO_ALL _TRO_LEADING _TRO_TRAILING
""".split())  # the last three: trim references, A1:.E10 (lookup/trimrange.py)

# the standard's functions (no prefix) that the evaluator does not implement
STANDARD_UNIMPLEMENTED = frozenset("""
CALL CUBEKPIMEMBER CUBERANKEDMEMBER CUBESET CUBESETCOUNT EUROCONVERT GETPIVOTDATA INFO JIS
PHONETIC REGISTER.ID SQL.REQUEST
""".split())


def unavailable(name: str, prefix: str, dialect: str, stored: bool) -> bool:
    """Is a call of ``name`` (upper case, written with ``prefix``) #NAME? in the dialect's
    application although the evaluator implements it? A future function without its
    prefix in a formula as a file stores it (``stored``), in Excel: a formula as a person
    types it (Microsoft's examples, the tests) names them without prefixes."""
    return stored and dialect == "excel" and not prefix and name in FUTURE


def known(name: str, implemented) -> bool:
    """Does Excel know ``name`` as a function (with its prefix where it needs one)?"""
    return name in implemented or name in FUTURE or name in STANDARD_UNIMPLEMENTED
