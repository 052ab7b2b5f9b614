"""formula/functions/textbytes.py: ASC changes widths only (the text means the same
under Unicode's compatibility normalisation, NFKC) and leaves no full-width ASCII and no
katakana that has a half-width form; Microsoft's example ASC("ＥＸＣＥＬ") is "EXCEL"; the
byte forms (LENB, LEFTB...) count as LEN, LEFT... do under a single-byte default
language (Microsoft's LENB page), checked against Python's str."""

from __future__ import annotations

import random
import unicodedata

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)
KATAKANA = [chr(k) for k in range(0x30A1, 0x30FB)]
FULL_ASCII = [chr(k) for k in range(0xFF01, 0xFF5F)]
POOL = KATAKANA + FULL_ASCII + list("abc XYZ 123") + ["\u3000", "漢", "ー", "。"]
HAS_HALF = {unicodedata.normalize("NFKC", chr(k)) for k in range(0xFF61, 0xFFA0)}


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def q(s: str) -> str:
    return '"' + s.replace('"', '""') + '"'


def test_asc_changes_widths_only():
    for _ in range(300):
        s = "".join(RNG.choice(POOL) for _ in range(RNG.randint(0, 12)))
        got = ev(f"=ASC({q(s)})")
        assert unicodedata.normalize("NFKC", got) == unicodedata.normalize("NFKC", s), s
        assert not any(ch in FULL_ASCII for ch in got), got
        assert not any(ch in HAS_HALF and ch in KATAKANA for ch in got), got
    assert ev('=ASC("ＥＸＣＥＬ")') == "EXCEL"
    assert ev('=ASC("ガ")') == "\uff76\uff9e"        # the voiced mark split off


@pytest.mark.parametrize("name", ["LEN", "LEFT", "RIGHT", "MID", "FIND", "SEARCH", "REPLACE"])
def test_byte_forms_count_characters(name):
    args = {"LEN": "{s}", "LEFT": "{s},3", "RIGHT": "{s},2", "MID": "{s},2,3",
            "FIND": '"b",{s}', "SEARCH": '"B",{s}', "REPLACE": '{s},2,1,"-"'}[name]
    for s in ("abcabc", "日本語のbテキスト", "ｶﾀｶﾅb"):
        text = args.format(s=q(s))
        assert ev(f"={name}B({text})") == ev(f"={name}({text})")
    assert ev(f'=LENB({q("日本語")})') == len("日本語")
