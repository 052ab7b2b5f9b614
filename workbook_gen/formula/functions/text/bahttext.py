"""BAHTTEXT: a number as Thai text with the suffix Baht (Microsoft's "BAHTTEXT function":
=BAHTTEXT(1234) is หนึ่งพันสองร้อยสามสิบสี่บาทถ้วน).

The number is rounded to the satang (a hundredth, half away from zero); the baht are read
in blocks of a million (ล้าน between blocks), each block by its digits and the words for
10 to 100,000 (สิบ ร้อย พัน หมื่น แสน), with Thai's two irregular tens: 10 is สิบ alone and
20 ยี่สิบ, and a final 1 after a ten is เอ็ด (11 สิบเอ็ด, 21 ยี่สิบเอ็ด; 101 หนึ่งร้อยหนึ่ง).
Then บาท, and the satang read the same way with สตางค์, or ถ้วน ("exactly") when there are
none; no baht and some satang is the satang alone; zero is ศูนย์บาทถ้วน; a negative number
starts with ลบ ("minus", even where it rounds to zero, as the ports of BAHTTEXT to
LibreOffice and Calligra do). What Microsoft Excel cached in formulas__test.xlsx (TEXT!R6:AW6: 0, 157, 65,
65.8, -1, an empty cell, TRUE, text, errors) agrees."""

from __future__ import annotations

from decimal import ROUND_HALF_UP, Decimal

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError

DIGITS = ("ศูนย์", "หนึ่ง", "สอง", "สาม", "สี่", "ห้า", "หก", "เจ็ด", "แปด", "เก้า")
PLACES = ((100_000, "แสน"), (10_000, "หมื่น"), (1_000, "พัน"), (100, "ร้อย"))
TEN, TWENTY, ELEVEN_END, MILLION = "สิบ", "ยี่", "เอ็ด", "ล้าน"
BAHT, SATANG, EXACTLY, MINUS = "บาท", "สตางค์", "ถ้วน", "ลบ"


def block(n: int) -> str:
    """1 <= n < 1,000,000 in words ("" for 0)."""
    out = []
    for size, word in PLACES:
        if n >= size:
            out.append(DIGITS[n // size] + word)
            n %= size
    tens, ones = divmod(n, 10)
    if tens:
        out.append(("" if tens == 1 else TWENTY if tens == 2 else DIGITS[tens]) + TEN)
    if ones:
        out.append(ELEVEN_END if tens and ones == 1 else DIGITS[ones])
    return "".join(out)


def baht_text(x: float) -> str:
    # the satang of the number as written (1.005 is 1 baht 1 satang; 1e15+1 keeps its 1)
    satang_total = int((Decimal(repr(abs(x))) * 100).quantize(Decimal(1), ROUND_HALF_UP))
    baht, satang = divmod(satang_total, 100)
    blocks = []
    while baht:
        baht, low = divmod(baht, 1_000_000)
        blocks.append(block(low))
    words = MILLION.join(reversed(blocks))
    if words:
        words += BAHT
    elif not satang:
        words = DIGITS[0] + BAHT
    words += block(satang) + SATANG if satang else EXACTLY
    return (MINUS if x < 0 else "") + words


@register("BAHTTEXT", 1, 1)
def _bahttext(ctx, number):
    x = c.to_number(number)
    return x if isinstance(x, ExcelError) else baht_text(x)
