"""Random well-typed formulas over random inputs, for the differential test against
LibreOffice (tests/formula/functions/test_dialect.py runs a seeded slice, bench/differential.py
thousands).

``cases(seed, n)`` draws ``n`` formulas from the families real workbooks use most: IF,
arithmetic and comparison with their coercions, SUM/AVERAGE/COUNT/COUNTA/COUNTIF/SUMIF and
their criteria, MATCH/VLOOKUP/INDEX, text (LEFT, MID, LEN, FIND, SUBSTITUTE, TEXT, ...), the
ROUND family and dates. Their operands are literals, cells and ranges of the Data sheet
(numbers, numeric and other text, booleans, errors, empty cells: drawn from the seed too) and
defined names. ``write_book`` puts the data and the formulas in one workbook; LibreOffice
recalculates it headless (one run for all cases) and ``compare`` sets its values beside the
evaluator's LibreOffice dialect.

``KNOWN`` lists the differences kept on purpose: each is a rule of LibreOffice 7.4 that our
LibreOffice dialect does not model, with the reason (Excel's behaviour, which the default
dialect follows, is documented by Microsoft and tested elsewhere).
"""

from __future__ import annotations

import math
import random
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import xlsxwriter

ROWS = 10  # the Data sheet's rows

# the Data sheet's columns: A numbers, B numeric and other text, C mixed (numbers, text,
# booleans, errors, empty), D dates (serials), E sorted numbers, F words for lookups
NUM, TXT, MIX, DAT, SRT, WRD = ("Data!$A$1:$A$10", "Data!$B$1:$B$10", "Data!$C$1:$C$10",
                                "Data!$D$1:$D$10", "Data!$E$1:$E$10", "Data!$F$1:$F$10")
TABLE = "Data!$E$1:$F$10"
NAMES = {"nums": NUM, "texts": TXT, "mixed": MIX, "dates": DAT, "sorted": SRT, "words": WRD,
         "table": TABLE, "first": "Data!$A$1"}

WORDS = ["apple", "pear", "apricot", "Banana", "kiwi", "cherry", "plum", "fig", "grape", "lime"]
NUMERIC_TEXT = ["5", "1.5", "-2", " 3 ", "1e2", "0", "10", "2.5E-1", "007"]
OTHER_TEXT = ["abc", "", "a*b", "x y", "Pear", "12abc", "-", "yes"]
FORMATS = ["0", "0.00", "#,##0", "#,##0.00", "0%", "0.0%", "yyyy-mm-dd", "dd/mm/yyyy",
           "mmm d, yyyy", "d-mmm-yy", "0.0E+00", "hh:mm", "h:mm AM/PM", "General", "000",
           "#,##0;(#,##0)", "$#,##0.00", "# ?/?", "@", "dddd", "mmmm"]


def data_values(rng: random.Random) -> dict[str, object]:
    """The Data sheet's cells: "A1" -> value ("=NA()" and "=1/0" are formulas, None empty)."""
    cells: dict[str, object] = {}
    for r in range(1, ROWS + 1):
        cells[f"A{r}"] = rng.choice([0, 1, -1, 2, 3, 5, 10, 0.5, -2.5, 3.7, 100, 1234.5678,
                                     rng.randint(-50, 50), round(rng.uniform(-100, 100), 3)])
        cells[f"B{r}"] = rng.choice(NUMERIC_TEXT + OTHER_TEXT + WORDS[:3])
        cells[f"D{r}"] = rng.choice([36526, 43831, 43890, 43891, 44196, 44255, 45000, 45351,
                                     367, 400, 40000.75, 2900000])
        cells[f"F{r}"] = WORDS[r - 1]
    # column C holds every kind: a boolean, an empty cell, two errors, numeric text
    mixed = [True, None, "=NA()", "=1/0", "4"] + [
        rng.choice([1, 2.5, -3, 0, "word", "", False, None, "apple", 7]) for _ in range(5)]
    rng.shuffle(mixed)
    for r, v in enumerate(mixed, 1):
        cells[f"C{r}"] = v
    values = sorted(rng.sample(range(1, 60), ROWS))
    for r, v in enumerate(values, 1):
        cells[f"E{r}"] = v
    return cells


class Gen:
    """Draws typed expressions: ``num``, ``text``, ``logical``, ``any``."""

    def __init__(self, rng: random.Random, depth: int = 3):
        self.rng, self.depth = rng, depth

    # ------------------------------------------------------------ leaves
    def cell(self, column: str | None = None) -> str:
        col = column or self.rng.choice("ABCD")
        last = ROWS if col == "D" else ROWS + 1  # row 11: an empty cell (not a date: AVOIDED)
        return f"Data!{col}{self.rng.randint(1, last)}"

    def number_literal(self) -> str:
        return self.rng.choice(["0", "1", "2", "3", "-1", "0.5", "2.5", "-2.5", "10", "100",
                                "3.14159", "1234.5678", "0.001", "7", "12", "1E3", "45000",
                                str(self.rng.randint(-20, 60))])

    def text_literal(self) -> str:
        return '"' + self.rng.choice(WORDS + NUMERIC_TEXT + OTHER_TEXT).replace('"', '""') + '"'

    def range_(self, kind: str = "any") -> str:
        pools = {"num": ["nums", NUM, "sorted", SRT, "Data!$A$1:$A$5", "dates"],
                 "any": ["mixed", MIX, "texts", TXT, "nums", "words", "Data!$A$1:$C$3",
                         "Data!$C$2:$C$8"],
                 "text": ["words", WRD, "texts", TXT]}
        return self.rng.choice(pools[kind])

    # ------------------------------------------------------------ typed expressions
    def num(self, d: int | None = None) -> str:
        d = self.depth if d is None else d
        if d <= 0:
            return self.rng.choice([self.number_literal, self.number_literal,
                                    lambda: self.cell("A"), lambda: self.cell()])()
        pick = self.rng.choice([
            self.number_literal, lambda: self.cell(), lambda: self.cell("A"),
            self.arith, self.arith, self.if_num, self.aggregate, self.aggregate, self.conditional,
            self.lookup_num, self.text_num, self.rounding, self.rounding, self.date_num,
            self.date_num, self.coerce_num, self.lookup_num])
        return pick(d - 1) if _wants_depth(pick) else pick()

    def text(self, d: int | None = None) -> str:
        d = self.depth if d is None else d
        if d <= 0:
            return self.rng.choice([self.text_literal, lambda: self.cell("B"),
                                    lambda: self.cell("F")])()
        pick = self.rng.choice([self.text_literal, lambda: self.cell("B"), self.text_fn,
                                self.text_fn, self.text_fn, self.concat, self.if_text,
                                self.lookup_text, self.format_text])
        return pick(d - 1) if _wants_depth(pick) else pick()

    def logical(self, d: int | None = None) -> str:
        d = self.depth if d is None else d
        r = self.rng
        if d <= 0:
            return r.choice(["TRUE", "FALSE", f"{self.num(0)}>{self.num(0)}"])
        pick = r.choice(["cmp", "cmp", "cmp", "andor", "not", "is", "exact", "lit"])
        if pick == "cmp":
            a, b = self.any(d - 1), self.any(d - 1)
            return f"{a}{r.choice(['=', '<>', '<', '>', '<=', '>='])}{b}"
        if pick == "andor":
            args = [self.logical(d - 1) for _ in range(r.randint(1, 3))]
            if r.random() < 0.2:
                args.append(self.range_("any"))
            return f"{r.choice(['AND', 'OR'])}({','.join(args)})"
        if pick == "not":
            return f"NOT({self.logical(d - 1)})"
        if pick == "is":
            fn = r.choice(["ISNUMBER", "ISTEXT", "ISBLANK", "ISERROR", "ISNA", "ISLOGICAL",
                           "ISERR", "ISNONTEXT", "ISEVEN", "ISODD"])
            arg = self.cell() if fn not in ("ISEVEN", "ISODD") else self.num(d - 1)
            return f"{fn}({arg})"
        if pick == "exact":
            return f"EXACT({self.text(d - 1)},{self.text(d - 1)})"
        return r.choice(["TRUE", "FALSE", "TRUE()", "FALSE()"])

    def any(self, d: int | None = None) -> str:
        d = self.depth if d is None else d
        return self.rng.choice([self.num, self.num, self.text, self.logical,
                                lambda _d: self.cell()])(d)

    # ------------------------------------------------------------ families
    def arith(self, d: int) -> str:
        r = self.rng
        op = r.choice(["+", "-", "*", "/", "^", "&"])
        if op == "&":
            return f"{self.any(d)}&{self.any(d)}"
        a = self.num(d) if r.random() < 0.8 else self.any(d)
        b = self.num(d) if r.random() < 0.8 else self.any(d)
        if op == "^":
            b = r.choice(["2", "0.5", "3", "-1", "0", "1/3"])
        form = r.choice(["{a}{op}{b}", "({a}){op}({b})", "-({a}){op}{b}", "{a}{op}{b}%"])
        return form.format(a=a, op=op, b=b)

    def if_num(self, d: int) -> str:
        if self.rng.random() < 0.2:
            return f"IFERROR({self.num(d)},{self.num(d)})"
        args = [self.logical(d), self.num(d)]
        if self.rng.random() < 0.85:
            args.append(self.num(d))
        return f"IF({','.join(args)})"

    def if_text(self, d: int) -> str:
        return f"IF({self.logical(d)},{self.text(d)},{self.text(d)})"

    def aggregate(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["SUM", "AVERAGE", "COUNT", "COUNTA", "MIN", "MAX", "COUNTBLANK",
                       "PRODUCT", "SUMPRODUCT", "MEDIAN"])
        if fn == "COUNTBLANK":
            return f"COUNTBLANK({self.range_('any')})"
        if fn == "SUMPRODUCT":
            return f"SUMPRODUCT({self.range_('num')},{r.choice([NUM, SRT, MIX])})"
        args = []
        for _ in range(r.randint(1, 3)):
            args.append(r.choice([self.range_("any"), self.range_("num"), self.num(d),
                                  self.cell(), self.text_literal(), "TRUE"]))
        return f"{fn}({','.join(args)})"

    def criteria(self, d: int) -> str:
        r = self.rng
        op = r.choice(["", "=", "<>", "<", ">", "<=", ">="])
        value = r.choice(WORDS[:4] + NUMERIC_TEXT[:4] + ["a*", "?e*", "*an*", "", "3", "10",
                                                          "0", "-2.5", "word"])
        form = r.random()
        if form < 0.6:
            return '"' + op + value + '"'
        if form < 0.8:
            return f'"{op}"&{self.num(max(d - 1, 0))}'
        return self.rng.choice([self.number_literal(), self.cell(), "TRUE"])

    def conditional(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["COUNTIF", "COUNTIF", "SUMIF", "SUMIF", "AVERAGEIF"])
        rng_ = self.range_(r.choice(["any", "num", "text"]))
        if fn == "COUNTIF":
            return f"COUNTIF({rng_},{self.criteria(d)})"
        if r.random() < 0.5 and rng_ in (MIX, TXT, WRD, "mixed", "texts", "words"):
            return f"{fn}({rng_},{self.criteria(d)},{r.choice([NUM, 'nums', SRT])})"
        return f"{fn}({rng_},{self.criteria(d)})"

    def lookup_num(self, d: int) -> str:
        r = self.rng
        kind = r.choice(["match", "match", "vlookup", "index", "index"])
        if kind == "match":
            what = r.choice([self.num(d), self.text_literal(), self.cell("F"), self.cell()])
            mode = r.choice(["", ",0", ",0", ",1", ",TRUE", ",FALSE"])
            # an approximate match needs a sorted range (Microsoft): else the answer is
            # the search algorithm's, which no documentation fixes
            where = r.choice([SRT, "sorted"] if mode in ("", ",1", ",TRUE")
                             else [SRT, "sorted", WRD, "words", NUM, MIX])
            return f"MATCH({what},{where}{mode})"
        if kind == "vlookup":
            what = self.num(d)
            return f"VLOOKUP({what},table,1{r.choice([',TRUE', ',FALSE', ''])})"
        area = r.choice([NUM, "nums", TABLE, "Data!$A$1:$C$10", SRT])
        two = area in (TABLE, "Data!$A$1:$C$10")
        row = r.choice([self.num(max(d - 1, 0)), str(r.randint(0, 11))])
        if two:
            return f"INDEX({area},{row},{r.randint(0, 3)})"
        return f"INDEX({area},{row})"

    def lookup_text(self, d: int) -> str:
        r = self.rng
        if r.random() < 0.5:
            return (f"VLOOKUP({self.num(d)},table,2"
                    f"{r.choice([',TRUE', ',FALSE', ''])})")
        return f"INDEX(words,{self.num(max(d - 1, 0))})"

    def text_num(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["LEN", "FIND", "SEARCH", "VALUE", "CODE"])
        if fn in ("FIND", "SEARCH"):
            needle = r.choice(['"a"', '"e"', '"p"', '"A"', '""', '"?"', '"*"', '"x"',
                               self.text(d)])
            extra = f",{self.num(max(d - 1, 0))}" if r.random() < 0.3 else ""
            return f"{fn}({needle},{self.text(d)}{extra})"
        return f"{fn}({self.text(d) if r.random() < 0.8 else self.num(d)})"

    def rounding(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["ROUND", "ROUNDUP", "ROUNDDOWN", "INT", "TRUNC", "MOD", "ABS",
                       "CEILING", "FLOOR", "SIGN", "SQRT", "MROUND", "EVEN", "ODD"])
        if fn in ("INT", "ABS", "SIGN", "SQRT", "EVEN", "ODD"):
            return f"{fn}({self.num(d)})"
        if fn == "TRUNC" and r.random() < 0.5:
            return f"TRUNC({self.num(d)})"
        digits = r.choice(["0", "1", "2", "-1", "-2", "3", "0.5", self.num(max(d - 1, 0))])
        if fn in ("MOD", "CEILING", "FLOOR", "MROUND"):
            digits = r.choice(["2", "3", "0.5", "-2", "1", "0.1", self.num(max(d - 1, 0))])
        return f"{fn}({self.num(d)},{digits})"

    def serial(self, d: int) -> str:
        """A date serial where both calendars agree: 1901-01-01 to 9999-12-31 (AVOIDED)."""
        r = self.rng
        return r.choice([self.cell("D"), str(r.choice([43891, 45000.5, 367, 36526])),
                         f"MOD(ABS({self.num(d)}),60000)+367"])

    def date_num(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["DATE", "YEAR", "MONTH", "DAY", "WEEKDAY", "EDATE", "EOMONTH",
                       "DAYS360", "HOUR", "MINUTE", "DATEVALUE", "TIME"])
        serial = self.serial(d)
        if fn == "DATE":
            return (f"DATE({r.choice(['2020', '2024', '1901', '99', f'2000+MOD({self.num(d)},50)'])},"
                    f"{r.choice(['1', '2', '13', '0', '-1', f'MOD({self.num(d)},40)'])},"
                    f"{r.choice(['1', '29', '31', '0', f'MOD({self.num(d)},60)'])})")
        if fn == "TIME":
            return f"TIME({r.randint(0, 30)},{r.randint(0, 90)},{r.randint(0, 70)})"
        if fn == "WEEKDAY":
            return f"WEEKDAY({serial}{r.choice(['', ',1', ',2', ',3'])})"
        if fn in ("EDATE", "EOMONTH"):
            months = r.choice(['1', '-1', '12', '0', '2.7', f'MOD({self.num(d)},30)'])
            return f"{fn}({serial},{months})"
        if fn == "DAYS360":
            return f"DAYS360({serial},{self.cell('D')}{r.choice(['', ',TRUE', ',FALSE'])})"
        if fn == "DATEVALUE":
            text = r.choice(["2020-03-01", "1/2/2021", "31-Dec-2020", "abc", "2020-02-30"])
            return f'DATEVALUE("{text}")'
        return f"{fn}({serial})"

    def coerce_num(self, d: int) -> str:
        r = self.rng
        return r.choice([f"N({self.cell()})", f"--{self.any(d)}", f"+{self.cell()}",
                         f"{self.cell()}*1", f"SUM({self.cell()},{self.cell()})",
                         f"{self.cell()}+{self.cell()}"])

    def text_fn(self, d: int) -> str:
        r = self.rng
        fn = r.choice(["LEFT", "RIGHT", "MID", "SUBSTITUTE", "UPPER", "LOWER", "TRIM",
                       "PROPER", "REPT", "REPLACE", "T"])
        t = self.text(d) if r.random() < 0.85 else self.num(d)
        n = r.choice(["0", "1", "2", "3", "5", "-1", self.num(max(d - 1, 0))])
        if fn in ("LEFT", "RIGHT"):
            return f"{fn}({t})" if r.random() < 0.2 else f"{fn}({t},{n})"
        if fn == "MID":
            return f"MID({t},{r.choice(['1', '2', '0', '4', n])},{n})"
        if fn == "SUBSTITUTE":
            inst = f",{r.choice(['1', '2', '0', n])}" if r.random() < 0.3 else ""
            old = r.choice(['"a"', '"p"', '""', '"5"', self.text(0)])
            new = r.choice(['"X"', '""', self.text(0)])
            return f"SUBSTITUTE({t},{old},{new}{inst})"
        if fn == "REPT":
            return f"REPT({t},{r.choice(['0', '1', '2', '3', '-1', '1.5'])})"
        if fn == "REPLACE":
            return f"REPLACE({t},{r.choice(['1', '2', '0'])},{r.choice(['1', '2', '0'])},{self.text(0)})"
        return f"{fn}({t})"

    def concat(self, d: int) -> str:
        if self.rng.random() < 0.5:
            return f"CONCATENATE({self.any(d)},{self.any(d)})"
        return f"{self.any(d)}&{self.any(d)}"

    def format_text(self, d: int) -> str:
        fmt = self.rng.choice(FORMATS)
        dated = any(ch in fmt for ch in "ymdh")
        return f'TEXT({self.serial(d) if dated else self.num(d)},"{fmt}")'


_DEPTH_METHODS = {"arith", "if_num", "if_text", "aggregate", "conditional", "lookup_num",
                  "lookup_text", "text_num", "rounding", "date_num", "coerce_num", "text_fn",
                  "concat", "format_text"}


def _wants_depth(fn) -> bool:
    return getattr(fn, "__name__", "") in _DEPTH_METHODS


def cases(seed: int, n: int) -> tuple[dict[str, object], list[str]]:
    """The Data sheet's cells and ``n`` formulas (texts without '='), drawn from ``seed``."""
    rng = random.Random(seed)
    data = data_values(rng)
    gen = Gen(rng)
    top = [gen.num, gen.num, gen.num, gen.text, gen.logical, gen.any]
    formulas = []
    while len(formulas) < n:
        f = rng.choice(top)()
        if len(f) < 400 and "(" in f and f not in formulas:
            formulas.append(f)
    return data, formulas


def write_book(path: Path, data: dict[str, object], formulas: list[str]) -> Path:
    """The Data sheet, the names and the formulas in Cases!A1:A<n>."""
    book = xlsxwriter.Workbook(str(path))
    sheet = book.add_worksheet("Data")
    for ref, value in data.items():
        if value is None:
            continue
        if isinstance(value, str) and value.startswith("="):
            sheet.write_formula(ref, value)
        elif isinstance(value, bool):
            sheet.write_boolean(ref, value)
        elif isinstance(value, str):
            sheet.write_string(ref, value)
        else:
            sheet.write_number(ref, value)
    for name, ref in NAMES.items():
        book.define_name(name, "=" + ref)
    cases_sheet = book.add_worksheet("Cases")
    for r, formula in enumerate(formulas):
        cases_sheet.write_formula(r, 0, "=" + formula)
    book.close()
    return path


# ---------------------------------------------------------------- comparing

def same(a, b) -> bool:
    """LibreOffice's value against ours: numbers to a relative 1e-9 (absolute 1e-12), text,
    booleans and errors equal, an empty text equal to an empty cell."""
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b or (isinstance(a, (int, float)) and isinstance(b, (int, float)) and a == b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if not (math.isfinite(a) and math.isfinite(b)):
            return a == b
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    if a in (None, "") and b in (None, ""):
        return True
    return type(a) is type(b) and a == b


@dataclass
class Difference:
    row: int
    formula: str
    libreoffice: object
    ours: object
    errors: frozenset = frozenset()  # the errors the formula's parts evaluate to (ours)

    @property
    def functions(self) -> list[str]:
        """The functions the formula calls, outermost first (``ops`` if none)."""
        return re.findall(r"([A-Z][A-Z0-9.]*)\(", self.formula) or ["ops"]


def _is_error(v) -> bool:
    from workbook_gen.xlerror import ExcelError
    return isinstance(v, ExcelError)


@dataclass(frozen=True)
class Known:
    """A LibreOffice rule our LibreOffice dialect does not model on purpose: ``explains``
    says whether a difference is this rule's, ``reason`` why it is kept."""
    name: str
    reason: str
    explains: Callable[[Difference], bool]


KNOWN: tuple[Known, ...] = (
    Known("which error wins",
          "Where two parts of a formula are errors, Excel returns the first in evaluation "
          "order (left to right, argument by argument); LibreOffice 7.4 carries errors as "
          "NaN payloads and which one survives depends on the operation (#N/A+#VALUE! is "
          "#N/A, #DIV/0!&#VALUE! is #VALUE!, a text argument's #VALUE! before a range's "
          "#DIV/0!): no rule to model. Explained only when both results are errors and "
          "LibreOffice's is one that a part of the formula evaluates to.",
          lambda d: _is_error(d.libreoffice) and _is_error(d.ours)
          and d.libreoffice in d.errors),
    Known("a very small or large number as text",
          "Excel writes a number in General format with an exponent below 1E-4 or so "
          "(2.27842333105491E-05, as our Excel dialect) and two exponent digits (E+46); "
          "LibreOffice 7.4 joins the decimal digits (0.0000227842333105491) and writes "
          "three (e+046). Not modelled: its rule is not documented.",
          lambda d: isinstance(d.ours, str) and isinstance(d.libreoffice, str)
          and re.search(r"\d[Ee][-+]\d", d.ours) is not None),
    Known("a wildcard in an inequality criterion",
          "Microsoft documents ? and * for criteria that match (=, <>); with <, >, <= or >= "
          "Excel compares the text as written, as our dialects do; LibreOffice 7.4 treats "
          "some such criteria as patterns (COUNTIF(B1:B10,\">?e*\")). Not modelled.",
          lambda d: re.search(r'"[<>]=?[^"]*[?*]', d.formula) is not None),
    Known("MROUND of different signs",
          "Microsoft: MROUND's number and multiple of different signs give #NUM!; "
          "LibreOffice 7.4 rounds (MROUND(5,-2) is 6); formula/functions/test_registry_libreoffice.py "
          "LO_DIFFERS keeps the same.",
          lambda d: "MROUND(" in d.formula and _is_error(d.ours)
          and d.ours.value == "#NUM!"),
)

# Divergences the generator keeps out of its formulas (each would otherwise fill the list):
AVOIDED = {
    "dates before 1900-03-01, before 1900 and after 9999":
        "LibreOffice counts days from 1899-12-30 without Lotus's 29 February 1900, so its "
        "serials 1-60 are a day earlier than Excel's (DAY(1) is 31 there) and it has dates "
        "before 1900 and after 9999 where Excel gives #NUM! (Microsoft: DATE's year is "
        "1900-9999). Date arguments are drawn from 1901 to 9999.",
    'the texts "TRUE" and "FALSE"':
        'LibreOffice converts them to 1 and 0 in arithmetic ("TRUE"*1 is 1) and a criterion '
        '"TRUE" matches them; Excel: #VALUE! and booleans only.',
    "approximate MATCH on an unsorted range":
        "Microsoft requires the range sorted; the answer on an unsorted one is the search "
        "algorithm's. Approximate modes draw sorted ranges only.",
}


def compare(formulas: list[str], theirs: dict, ours: dict, parts=None):
    """(differences not explained, differences KNOWN explains) between LibreOffice's values
    and ours, keyed by row (1-based) of the Cases sheet; ``parts(formula)``: the errors
    its parts evaluate to."""
    new, known = [], []
    for row, formula in enumerate(formulas, 1):
        a, b = theirs.get(row), ours.get(row)
        if same(a, b):
            continue
        d = Difference(row, formula, a, b, parts(formula) if parts else frozenset())
        (known if any(k.explains(d) for k in KNOWN) else new).append(d)
    return new, known


def _parts(inputs, result):
    """``parts(formula)``: the errors that the formula's calls, operators and cells
    evaluate to with our LibreOffice dialect."""
    from workbook_gen.auditor.recomputed import Recomputed, RecomputedResolver
    from workbook_gen.formula import ast, parse
    from workbook_gen.formula.scalar import evaluate as evaluate_scalar
    from workbook_gen.xlerror import ExcelError

    value_of = Recomputed(result, inputs.constants)

    def parts(formula: str) -> frozenset:
        resolver = RecomputedResolver(value_of, inputs.book.defined_names, "Cases",
                                      inputs.is_formula)
        found = set()
        for name, ref in NAMES.items():  # the parts evaluated alone: names as their ranges
            formula = re.sub(rf"(?<![\w!$.]){name}(?![\w(])", ref, formula)
        for node in ast.walk(parse("=" + formula)):
            if isinstance(node, (ast.RangeRef, ast.Name)):  # the errors in its cells
                ref = node if isinstance(node, ast.RangeRef) else _name_range(node.name)
                if ref is not None:
                    found.update(v for row in resolver.range(
                        ref.sheet, ref.first.row, ref.first.col, ref.last.row,
                        ref.last.col) for v in row if _is_error(v))
                continue
            if isinstance(node, ast.Func):  # a text argument of an aggregate: #VALUE!
                for arg in node.args:
                    if isinstance(arg, ast.String) and arg.value.strip():
                        found.add(ExcelError.VALUE)
            if isinstance(node, (ast.Func, ast.Binary, ast.Unary, ast.CellRef, ast.Percent)):
                try:
                    v = evaluate_scalar(node, resolver, dialect="libreoffice")
                except Exception:  # noqa: BLE001 - a part that cannot stand alone
                    continue
                if _is_error(v):
                    found.add(v)
        return frozenset(found)

    def _name_range(name: str):
        ref = parse("=" + NAMES.get(name.lower(), "#REF!"))
        return ref if isinstance(ref, ast.RangeRef) else None
    return parts


def run(folder: Path, seed: int, n: int, *, timeout: float = 600):
    """Write, recalculate in LibreOffice (one run) and evaluate ``n`` cases of ``seed``:
    (formulas, LibreOffice's values, ours), values keyed by the Cases row."""
    from workbook_gen.auditor.inputs import read_inputs
    from workbook_gen.engines.libreoffice import recalculate
    from workbook_gen.evaluator import evaluate_cells

    data, formulas = cases(seed, n)
    src = write_book(folder / f"differential-{seed}.xlsx", data, formulas)
    saved = recalculate(src, folder / "lo", timeout=timeout)
    inputs = read_inputs(saved)
    result = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                            dialect="libreoffice", book=inputs.book_info())
    theirs = {k[1]: v for k, v in inputs.cached.items() if k[0] == "Cases"}
    ours = {k[1]: result.values[k] if k in result.values else ("not evaluated",
                                                               result.not_checked.get(k))
            for k in inputs.formulas if k[0] == "Cases"}
    return formulas, theirs, ours, _parts(inputs, result)
