"""A lossless tokenizer for Excel formulas (A1 notation).

Modelled on openpyxl's ``formula/tokenizer.py``: a dispatch table maps the first
character of a token to a consumer. Every character of the input ends up in exactly
one token, whitespace included, so ``render(tokenize(text)) == text``.

A reference with its sheet and range (``'Other Sheet'!$A$2:$A$38``) is one REF token;
``+``/``-`` are told apart as PREFIX or INFIX from the token before them.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from workbook_gen.cellref import column_number  # noqa: F401  (part of this module's face)
from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.xlerror import ExcelError

# Token kinds
START = "START"          # the leading '='
NUMBER = "NUMBER"
STRING = "STRING"
BOOL = "BOOL"
ERROR = "ERROR"
REF = "REF"              # cell or range, optionally sheet-qualified
NAME = "NAME"            # defined name, optionally sheet-qualified
FUNC = "FUNC"            # function name with its '(' : "SIN("
OPEN = "OPEN"            # '(' of a parenthesised expression
CLOSE = "CLOSE"          # ')' of a function or of a parenthesis
SEP = "SEP"              # ',' between function arguments
PREFIX = "PREFIX"        # unary + -
INFIX = "INFIX"          # binary operators, ':' included
POSTFIX = "POSTFIX"      # %
WSPACE = "WSPACE"
ARRAY = "ARRAY"          # an array constant, braces included: "{1,2;3,4}"
STRUCT = "STRUCT"        # a structured reference: "Table1[Amount]", "[@x]"

OPERAND_KINDS = frozenset({NUMBER, STRING, BOOL, ERROR, REF, NAME, ARRAY, STRUCT})
# After these a '+' or '-' is unary.
_PREFIX_CONTEXT = frozenset({START, OPEN, FUNC, SEP, PREFIX, INFIX, None})


@dataclass(frozen=True, slots=True)
class Token:
    kind: str
    text: str
    pos: int  # offset of the first character in the formula text


def describe(text: str, pos: int, what: str) -> str:
    """The standard message: ``<what> at position <pos> in '<text>'``."""
    return f"{what} at position {pos} in '{text}'"


# Excel's names take letters of any script: here, every character from U+00A1 on. The
# classes are spelled negated, by what they leave out: the re module maps a range such as
# \u00a1-\uffff into its table a character at a time (about 9 ms a class, 0.12 s for
# this module's patterns at every start-up), an excluded ASCII range costs nothing.
_FIRST = r"[^\x00-@\[\]^`{-\xa0\U00010000-\U0010ffff]"  # [A-Za-z_\\\u00a1-\uffff]
_NEXT = r"[^\x00-\-/:-@\[-^`{-\xa0]"                   # [\w.] and U+00A1 on
_SHEET_NAME = rf"{_FIRST}{_NEXT}*"
_SHEET = rf"(?:'(?:[^']|'')+'|{_SHEET_NAME}(?::{_SHEET_NAME})?)!"  # 3-D: Sheet1:Sheet3!
_CELL = r"\$?[A-Za-z]{1,3}\$?[0-9]{1,7}"
_END = r"(?![^\x00- \"-'\)-\-/:-@\\\]^`{-\xa0])"  # not before [\w.(!\[] or U+00A1 on
_REF_RE = re.compile(rf"(?:{_SHEET})?{_CELL}(?::{_CELL})?{_END}")
_COLS_RE = re.compile(rf"(?:{_SHEET})?\$?[A-Za-z]{{1,3}}:\$?[A-Za-z]{{1,3}}{_END}")
_ROWS_RE = re.compile(rf"(?:{_SHEET})?\$?[0-9]{{1,7}}:\$?[0-9]{{1,7}}{_END}")
_SHEET_ERROR_RE = re.compile(rf"{_SHEET}#REF!")  # a deleted reference: 'Sheet 1'!#REF!
_WORD_RE = re.compile(rf"(?:{_SHEET})?{_FIRST}[^\x00-\-/:->@\[\]^`{{-\xa0]*")  # _NEXT, ? and \\
_NUMBER_RE = re.compile(r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_STRING_RE = re.compile(r'"(?:[^"]|"")*"')
_ERROR_RE = re.compile("|".join(re.escape(e.value) for e in sorted(
    ExcelError, key=lambda e: -len(e.value))), re.IGNORECASE)
_EXTERNAL_RE = re.compile(r"\[\d+\]")
_THIS_BOOK_RE = re.compile(r"\[0\]!")  # "[0]!name": a name of this workbook (Excel for Mac)
_WSPACE_RE = re.compile(r"[ \n\r\t]+")
WHOLE_COL = re.compile(r"(\$?)([A-Za-z]{1,3})")
WHOLE_ROW = re.compile(r"(\$?)([0-9]{1,7})")
CELL_PARTS = re.compile(r"(\$?)([A-Za-z]{1,3})(\$?)([0-9]+)")


def is_cell_ref(text: str) -> bool:
    """True for ``A1`` .. ``XFD1048576`` (with or without ``$``)."""
    m = CELL_PARTS.fullmatch(text)
    return bool(m) and column_number(m.group(2)) <= 16_384 and 1 <= int(m.group(4)) <= 1_048_576


class Tokenizer:
    """Split a formula into tokens; ``items`` holds them, ``render()`` joins them back."""

    def __init__(self, formula: str):
        self.formula = formula
        self.items: list[Token] = []
        self.offset = 0
        self._parse()

    def _parse(self) -> None:
        dispatch = {}
        consumers = (
            ('"', self._string),
            ("#", self._error),
            (" \n\r\t", self._whitespace),
            ("0123456789.", self._number),
            ("+-*/^&=<>%:~", self._operator),  # '~': union as LibreOffice saves it
            ("(", self._open),
            (")", self._close),
            (",", self._separator),
            ("{", self._array),
            ("[", self._bracket),
        )
        for chars, consumer in consumers:
            dispatch.update(dict.fromkeys(chars, consumer))
        if self.formula.startswith("="):
            self._add(START, "=")
        while self.offset < len(self.formula):
            ch = self.formula[self.offset]
            consumer = dispatch.get(ch)
            if consumer is None:
                consumer = self._word if (ch.isalpha() or ch in "_\\$'" or ord(ch) > 160) \
                    else self._unexpected
            consumer()

    # -- helpers -------------------------------------------------------------------
    def _add(self, kind: str, text: str) -> None:
        self.items.append(Token(kind, text, self.offset))
        self.offset += len(text)

    def _last_kind(self) -> str | None:
        for token in reversed(self.items):
            if token.kind != WSPACE:
                return token.kind
        return None

    def _fail(self, what: str) -> None:
        raise FormulaSyntaxError(describe(self.formula, self.offset, what))

    def _unexpected(self) -> None:
        ch = self.formula[self.offset]
        if ch == ";":
            self._fail("unexpected ';' (argument separator must be ',')")
        self._fail(f"unexpected character {ch!r}")

    # -- consumers -----------------------------------------------------------------
    def _string(self) -> None:
        m = _STRING_RE.match(self.formula, self.offset)
        if m is None:
            self._fail("unterminated string")
        self._add(STRING, m.group(0))

    def _error(self) -> None:
        m = _ERROR_RE.match(self.formula, self.offset)
        if m is None:
            self._fail("unknown error literal")
        self._add(ERROR, m.group(0))

    def _whitespace(self) -> None:
        self._add(WSPACE, _WSPACE_RE.match(self.formula, self.offset).group(0))

    def _number(self) -> None:
        rows = _ROWS_RE.match(self.formula, self.offset)
        if rows:
            self._add(REF, rows.group(0))
            return
        m = _NUMBER_RE.match(self.formula, self.offset)
        if m is None:
            self._fail("unexpected '.'")
        self._add(NUMBER, m.group(0))

    def _operator(self) -> None:
        two = self.formula[self.offset:self.offset + 2]
        if two in ("<>", "<=", ">="):
            self._add(INFIX, two)
            return
        ch = self.formula[self.offset]
        if ch == "%":
            self._add(POSTFIX, ch)
        elif ch in "+-" and self._last_kind() in _PREFIX_CONTEXT:
            self._add(PREFIX, ch)
        else:
            self._add(INFIX, ch)

    def _open(self) -> None:
        self._add(OPEN, "(")

    def _close(self) -> None:
        self._add(CLOSE, ")")

    def _separator(self) -> None:
        self._add(SEP, ",")

    def _array(self) -> None:
        """``{...}`` up to its closing brace (strings may hold braces)."""
        at = self.offset + 1
        while at < len(self.formula) and self.formula[at] != "}":
            if self.formula[at] == '"':
                m = _STRING_RE.match(self.formula, at)
                if m is None:
                    break
                at = m.end()
            else:
                at += 1
        if at >= len(self.formula):
            self._fail("unclosed '{'")
        self._add(ARRAY, self.formula[self.offset:at + 1])

    def _brackets(self, at: int) -> int:
        """End offset of the balanced ``[...]`` group starting at ``at`` (``'`` escapes)."""
        depth = 0
        while at < len(self.formula):
            ch = self.formula[at]
            if ch == "'":
                at += 2
                continue
            if ch == "[":
                depth += 1
            elif ch == "]":
                depth -= 1
                if depth == 0:
                    return at + 1
            at += 1
        self._fail("unclosed '['")

    def _bracket(self) -> None:
        book = _EXTERNAL_RE.match(self.formula, self.offset)
        if book:
            at = book.end()
            if self.formula.startswith("!", at):  # [n]!Name: a name of that workbook
                m = _WORD_RE.match(self.formula, at + 1)
                if m is not None:
                    self._add(NAME, self.formula[self.offset:m.end()])
                    return
            for regex in (_REF_RE, _COLS_RE, _ROWS_RE, _WORD_RE):  # [n]Sheet!A1, [n]Sheet!Name
                m = regex.match(self.formula, at)
                if m and "!" in m.group(0) and (regex is not _WORD_RE or
                                                not self.formula.startswith("(", m.end())):
                    self._add(REF if regex is not _WORD_RE else NAME,
                              self.formula[self.offset:m.end()])
                    return
            self._fail("external reference (to another workbook) at '['")
        self._add(STRUCT, self.formula[self.offset:self._brackets(self.offset)])

    def _word(self) -> None:
        for regex in (_REF_RE, _COLS_RE, _ROWS_RE):
            m = regex.match(self.formula, self.offset)
            if m and self._valid_ref(m.group(0)):
                self._add(REF, m.group(0))
                return
        m = _SHEET_ERROR_RE.match(self.formula, self.offset)
        if m is not None:
            self._add(ERROR, m.group(0))
            return
        m = _WORD_RE.match(self.formula, self.offset)
        if m is None:
            if self.formula[self.offset] == "'":
                self._fail("unterminated quoted sheet name")
            self._fail(f"unexpected character {self.formula[self.offset]!r}")
        word = m.group(0)
        end = self.offset + len(word)
        if end < len(self.formula) and self.formula[end] == "[" and "!" not in word:
            self._add(STRUCT, self.formula[self.offset:self._brackets(end)])
        elif end < len(self.formula) and self.formula[end] == "(" and "!" not in word:
            self._add(FUNC, word + "(")
        elif word.upper() in ("TRUE", "FALSE"):
            self._add(BOOL, word)
        else:
            self._add(NAME, word)

    @staticmethod
    def _valid_ref(text: str) -> bool:
        body = split_sheet(text)[1]
        parts = body.split(":")
        if CELL_PARTS.fullmatch(parts[0]):
            return all(is_cell_ref(p) for p in parts)
        return True  # whole rows / columns: the parser rejects them with a message

    def render(self) -> str:
        return "".join(t.text for t in self.items)


def split_sheet(text: str) -> tuple[str | None, str]:
    """``"'It''s'!A1"`` -> ``("It's", "A1")``; ``"A1"`` -> ``(None, "A1")``."""
    if "!" not in text:
        return None, text
    sheet, _, rest = text.rpartition("!")
    if sheet.startswith("'"):
        sheet = sheet[1:-1].replace("''", "'")
    return sheet, rest


def tokenize(formula: str) -> list[Token]:
    """The tokens of ``formula`` (with or without the leading ``=``)."""
    return Tokenizer(formula).items
