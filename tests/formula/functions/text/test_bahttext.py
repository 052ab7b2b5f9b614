"""text/bahttext.py: BAHTTEXT against Microsoft's page (support.microsoft.com/en-us/excel/
bahttext-function: =BAHTTEXT(1234) is หนึ่งพันสองร้อยสามสิบสี่บาทถ้วน), Microsoft Excel's cached
values in formulas__test.xlsx (TEXT!R6:AW6), and Thai numerals read digit by digit by a
reference written here (the place words, สิบ alone for 10, ยี่สิบ for 20, เอ็ด for a final 1
after a ten, ล้าน between blocks of six digits)."""

from __future__ import annotations

import random
import re
import zipfile

import pytest

from tests.formula.functions import excel_cached as xc
from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

DIGIT = "ศูนย์ หนึ่ง สอง สาม สี่ ห้า หก เจ็ด แปด เก้า".split()
PLACE = ["", "สิบ", "ร้อย", "พัน", "หมื่น", "แสน"]


def ev(text: str, res=None):
    return evaluate_array(parse(text), res or DictResolver({}), "excel", None)


def thai(n: int) -> str:
    """n >= 1 read digit by digit, right to left within each block of six."""
    if n >= 1_000_000:
        high, low = divmod(n, 1_000_000)
        return thai(high) + "ล้าน" + (thai(low) if low else "")
    digits = [int(d) for d in str(n)][::-1]
    words = []
    for place, d in enumerate(digits):
        if d == 0:
            continue
        if place == 1:
            words.append({1: "", 2: "ยี่"}.get(d, DIGIT[d]) + "สิบ")
        elif place == 0 and d == 1 and len(digits) > 1 and digits[1] != 0:
            words.append("เอ็ด")
        else:
            words.append(DIGIT[d] + PLACE[place])
    return "".join(reversed(words))


def test_the_example_of_microsofts_page():
    assert ev("BAHTTEXT(1234)") == "หนึ่งพันสองร้อยสามสิบสี่บาทถ้วน"


def test_every_bahttext_of_formulas_test_agrees_with_excel():
    res = xc.resolver(("TEXT",), 6, 6)
    with zipfile.ZipFile(xc.PATH) as z:
        text = z.read("xl/worksheets/sheet14.xml").decode()
    row = xc.book()["TEXT"]
    checked = 0
    for col, formula in re.findall(r'<c r="([A-Z]+)6"[^>]*><f>(BAHTTEXT\([^<]*)</f>', text):
        assert xc.same(ev(formula, res), xc.value(row[f"{col}6"].value)), formula
        checked += 1
    assert checked >= 2
    for anchor, ref, formula in xc.array_formulas("sheet14", r"BAHTTEXT"):
        xc.assert_spill(formula, ref, "TEXT", res)


@pytest.mark.parametrize("seed", range(8))
def test_baht_and_satang_read_as_thai_numerals(seed):
    rng = random.Random(seed)
    for _ in range(200):
        baht = rng.choice([rng.randint(1, 99), rng.randint(100, 10 ** 6),
                           rng.randint(10 ** 6, 10 ** 13)])
        satang = rng.randint(0, 99)
        x = float(f"{baht}.{satang:02d}")
        want = thai(baht) + "บาท" + (thai(satang) + "สตางค์" if satang else "ถ้วน")
        assert ev(f"BAHTTEXT({x!r})") == want, x
        assert ev(f"BAHTTEXT(-{x!r})") == "ลบ" + want, x


def test_edges():
    assert ev("BAHTTEXT(0)") == "ศูนย์บาทถ้วน"
    assert ev("BAHTTEXT(0.5)") == "ห้าสิบสตางค์"        # no baht: the satang alone
    assert ev("BAHTTEXT(1.005)") == "หนึ่งบาทหนึ่งสตางค์"  # rounded half up, as written
    assert ev("BAHTTEXT(11000000)") == "สิบเอ็ดล้านบาทถ้วน"
    assert ev('BAHTTEXT("x")') == ExcelError.VALUE
