"""The IM* functions and COMPLEX (formula/functions/complex.py) against Python's cmath:
each result, read back from Excel's text form ("a+bi", 15 significant digits), within
1e-13 of cmath's on random arguments; Microsoft's worked examples; the text form itself."""

from __future__ import annotations

import cmath
import math
import random
import re

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

UNARY = {
    "IMSQRT": cmath.sqrt, "IMLN": cmath.log, "IMLOG10": cmath.log10,
    "IMLOG2": lambda z: cmath.log(z) / math.log(2), "IMEXP": cmath.exp,
    "IMSIN": cmath.sin, "IMCOS": cmath.cos, "IMTAN": cmath.tan,
    "IMCOT": lambda z: 1 / cmath.tan(z), "IMSEC": lambda z: 1 / cmath.cos(z),
    "IMCSC": lambda z: 1 / cmath.sin(z), "IMSINH": cmath.sinh, "IMCOSH": cmath.cosh,
    "IMCONJUGATE": lambda z: z.conjugate(),
}
NUMBER = {"IMABS": abs, "IMREAL": lambda z: z.real, "IMAGINARY": lambda z: z.imag,
          "IMARGUMENT": cmath.phase}
BINARY = {"IMSUM": lambda a, b: a + b, "IMSUB": lambda a, b: a - b,
          "IMPRODUCT": lambda a, b: a * b, "IMDIV": lambda a, b: a / b}


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def read(text: str) -> complex:
    """Excel's complex text ("3+4i", "-i", "1.5", "2E-16+i") as a Python complex."""
    m = re.fullmatch(r"([+-]?[\d.]+(?:E[+-]?\d+)?)?(?:([+-]?[\d.]*(?:E[+-]?\d+)?)([ij]))?",
                     text)
    assert m and text, text
    real = float(m.group(1)) if m.group(1) else 0.0
    imag = 0.0
    if m.group(3):
        sign_digits = m.group(2)
        imag = float(sign_digits + "1") if sign_digits in ("", "+", "-") else float(sign_digits)
    return complex(real, imag)


def show(z: complex) -> str:
    return f"{z.real!r}{z.imag:+.17g}i"


def close(a: complex, b: complex) -> bool:
    return abs(a - b) <= 1e-13 * max(1.0, abs(b))


def samples(seed: str, n: int = 60) -> list[complex]:
    rng = random.Random(seed)
    return [complex(rng.uniform(-4, 4), rng.uniform(-4, 4)) for _ in range(n)]


@pytest.mark.parametrize("name", sorted(UNARY))
def test_complex_valued_functions_as_cmath(name):
    for z in samples(name):
        got = ev(f'={name}("{show(z)}")')
        assert close(read(got), UNARY[name](z)), (name, z, got)


@pytest.mark.parametrize("name", sorted(NUMBER))
def test_number_valued_functions_as_cmath(name):
    for z in samples(name):
        assert ev(f'={name}("{show(z)}")') == pytest.approx(NUMBER[name](z), rel=1e-14,
                                                          abs=1e-15)


@pytest.mark.parametrize("name", sorted(BINARY))
def test_two_argument_functions_as_cmath(name):
    zs = samples(name, 80)
    for a, b in zip(zs[::2], zs[1::2]):
        got = ev(f'={name}("{show(a)}","{show(b)}")')
        assert close(read(got), BINARY[name](a, b)), (name, a, b, got)


def test_impower_as_the_principal_power():
    for z in samples("IMPOWER"):
        for n in (2, 3, -1, 0.5, 2.5):
            got = ev(f'=IMPOWER("{show(z)}",{n})')
            assert close(read(got), cmath.exp(n * cmath.log(z))), (z, n, got)


def test_microsofts_examples_and_the_text_form():
    assert ev('=IMSUM("3+4i","5-3i")') == "8+i"
    assert ev('=IMSUB("13+4i","5+3i")') == "8+i"
    assert ev('=IMPRODUCT("3+4i","5-3i")') == "27+11i"
    assert ev('=IMDIV("-238+240i","10+24i")') == "5+12i"
    assert ev('=IMABS("5+12i")') == 13
    assert ev("=COMPLEX(3,4)") == "3+4i"
    assert ev('=COMPLEX(3,4,"j")') == "3+4j"
    assert ev("=COMPLEX(0,1)") == "i"
    assert ev("=COMPLEX(0,-1)") == "-i"
    assert ev("=COMPLEX(1.5,0)") == "1.5"
    assert ev('=COMPLEX(3,4,"k")') == ExcelError.VALUE   # suffix i or j only
    assert ev('=IMDIV("1","0")') == ExcelError.NUM
    assert ev('=IMABS("3+4x")') == ExcelError.NUM         # not a complex number
