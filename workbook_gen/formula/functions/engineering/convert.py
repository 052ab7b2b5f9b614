"""CONVERT: a number from one unit to another, by Excel's unit table (SI and binary
prefixes; temperatures by their scales)."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError

# unit -> (quantity, factor to the quantity's base unit, prefixes allowed)
_UNITS: dict[str, tuple[str, float, bool]] = {}


def _add(quantity: str, prefixed: bool, table: dict[str, float]) -> None:
    for names, factor in table.items():
        for name in names.split():
            _UNITS[name] = (quantity, factor, prefixed)


_IN = 0.0254
_add("mass", True, {"g": 1.0, "u": 1.660538782e-24})  # (Excel's u: formulas__test EXTRA!U5)
_add("mass", False, {"sg": 14593.9029372064, "lbm": 453.59237, "ozm": 28.349523125,
                     "grain": 0.06479891, "cwt shweight": 45359.237,
                     "uk_cwt lcwt hweight": 50802.34544, "stone": 6350.29318,
                     "ton": 907184.74, "uk_ton LTON brton": 1016046.9088})
_add("distance", True, {"m": 1.0, "ang": 1e-10, "ly": 9460730472580800.0,
                        "parsec pc": 30856775812815500.0})
_add("distance", False, {"mi": 1609.344, "Nmi": 1852.0, "in": _IN, "ft": 0.3048, "yd": 0.9144,
                         "ell": 1.143, "Picapt Pica": _IN / 72, "pica": _IN / 6,
                         "survey_mi": 1609.34721869444})
_add("time", True, {"sec s": 1.0})
_add("time", False, {"yr": 31557600.0, "day d": 86400.0, "hr": 3600.0, "mn min": 60.0})
_add("pressure", True, {"Pa p": 1.0, "atm at": 101325.0, "mmHg": 133.322})
_add("pressure", False, {"psi": 6894.75729316836, "Torr": 133.322368421053})
_add("force", True, {"N": 1.0, "dyn dy": 1e-5, "pond": 0.00980665})
_add("force", False, {"lbf": 4.4482216152605})
_add("energy", True, {"J": 1.0, "e": 1e-7, "c": 4.184, "cal": 4.1868, "eV ev": 1.602176487e-19,
                      "Wh wh": 3600.0})
_add("energy", False, {"HPh hh": 2684519.53769617, "flb": 1.3558179483314,
                       "BTU btu": 1055.05585262})
_add("power", True, {"W w": 1.0})
_add("power", False, {"HP h": 745.69987158227, "PS": 735.49875})
_add("magnetism", True, {"T": 1.0, "ga": 1e-4})
_add("volume", True, {"l L lt": 1e-3, "m3 m^3": 1.0, "ang3 ang^3": 1e-30,
                      "uk_pt": 5.6826125e-4})  # (Excel takes prefixes on uk_pt, and on mph)
_add("volume", False, {"tsp": 4.92892159375e-6, "tspm": 5e-6, "tbs": 1.478676478125e-5,
                       "oz": 2.95735295625e-5, "cup": 2.365882365e-4, "pt us_pt": 4.73176473e-4,
                       "qt": 9.46352946e-4, "uk_qt": 1.1365225e-3,
                       "gal": 3.785411784e-3, "uk_gal": 4.54609e-3, "barrel": 0.158987294928,
                       "bushel": 0.03523907016688, "ft3 ft^3": 0.028316846592,
                       "in3 in^3": 1.6387064e-5, "yd3 yd^3": 0.764554857984,
                       "mi3 mi^3": 4168181825.44058, "Nmi3 Nmi^3": 6352182208.0,
                       "ly3 ly^3": 9460730472580800.0 ** 3,
                       "Picapt3 Picapt^3 Pica3 Pica^3": (_IN / 72) ** 3,
                       "GRT regton": 2.8316846592, "MTON": 1.13267386368})
_add("area", True, {"m2 m^2": 1.0, "ar": 100.0, "ang2 ang^2": 1e-20})
_add("area", False, {"uk_acre": 4046.8564224, "us_acre": 4046.87260987425,
                     "ft2 ft^2": 0.09290304, "ha": 10000.0, "in2 in^2": 0.00064516,
                     "mi2 mi^2": 2589988.110336, "Nmi2 Nmi^2": 3429904.0,
                     "yd2 yd^2": 0.83612736, "Morgen": 2500.0,
                     "ly2 ly^2": 9460730472580800.0 ** 2,
                     "Picapt2 Picapt^2 Pica2 Pica^2": (_IN / 72) ** 2})
_add("information", True, {"bit": 1.0, "byte": 8.0})
_add("speed", True, {"m/s m/sec": 1.0, "m/h m/hr": 1 / 3600, "mph": 0.44704})
_add("speed", False, {"kn": 1852 / 3600, "admkn": 6080 * 0.3048 / 3600})
_TEMPERATURE = {"C": "C", "cel": "C", "F": "F", "fah": "F", "K": "K", "kel": "K",
                "Rank": "R", "Reau": "Re"}

_PREFIXES = {"Y": 1e24, "Z": 1e21, "E": 1e18, "P": 1e15, "T": 1e12, "G": 1e9, "M": 1e6,
             "k": 1e3, "h": 1e2, "da": 1e1, "e": 1e1, "d": 1e-1, "c": 1e-2, "m": 1e-3,
             "u": 1e-6, "n": 1e-9, "p": 1e-12, "f": 1e-15, "a": 1e-18, "z": 1e-21, "y": 1e-24}
_BINARY = {"Yi": 2.0 ** 80, "Zi": 2.0 ** 70, "Ei": 2.0 ** 60, "Pi": 2.0 ** 50, "Ti": 2.0 ** 40,
           "Gi": 2.0 ** 30, "Mi": 2.0 ** 20, "ki": 2.0 ** 10}


def _units(name: str) -> list:
    """Every reading of a unit name as (quantity, factor): the unit itself first, then a
    prefix and a unit (Excel reads "pc" as a parsec, or as a picocalorie next to "J")."""
    out = []
    if name in _UNITS:
        q, f, _ = _UNITS[name]
        out.append((q, f))
    if name in _TEMPERATURE:
        out.append(("temperature", _TEMPERATURE[name]))
    for table in (_BINARY, _PREFIXES):
        for p, scale in table.items():
            rest = name[len(p):]
            if name.startswith(p) and rest in _UNITS and _UNITS[rest][2]:
                if table is _BINARY and _UNITS[rest][0] != "information":
                    continue
                q, f, _ = _UNITS[rest]
                if rest.endswith("2") and q == "area":   # a prefix of a length, squared
                    scale **= 2
                elif rest.endswith("3") and q == "volume":
                    scale **= 3
                out.append((q, f * scale))
            if name.startswith(p) and rest in ("K", "kel"):
                out.append(("temperature", ("K", scale)))
    return out


def _pair(a: str, b: str):
    """The readings of two unit names that measure the same quantity, or None."""
    for ua in _units(a):
        for ub in _units(b):
            if ua[0] == ub[0]:
                return ua, ub
    return None


def _to_kelvin(x: float, scale) -> float:
    unit, factor = scale if isinstance(scale, tuple) else (scale, 1.0)
    x *= factor
    return {"C": x + 273.15, "F": (x - 32) * 5 / 9 + 273.15, "K": x, "R": x * 5 / 9,
            "Re": x * 1.25 + 273.15}[unit]


def _from_kelvin(k: float, scale) -> float:
    unit, factor = scale if isinstance(scale, tuple) else (scale, 1.0)
    x = {"C": k - 273.15, "F": (k - 273.15) * 9 / 5 + 32, "K": k, "R": k * 9 / 5,
         "Re": (k - 273.15) * 0.8}[unit]
    return x / factor


@register("CONVERT", 3, 3)
def _convert(ctx, value, src, dst):
    if isinstance(value, bool):  # Analysis ToolPak functions take no booleans
        return ExcelError.VALUE  # (formulas test.xlsx ENGINEERING!Y16)
    x = c.to_number(value)
    if isinstance(x, ExcelError):
        return x
    a, b = c.to_text(src), c.to_text(dst)
    for t in (a, b):
        if isinstance(t, ExcelError):
            return t
    pair = _pair(a, b)
    if pair is None:
        return ExcelError.NA
    ua, ub = pair
    if ua[0] == "temperature":
        return c.result(_from_kelvin(_to_kelvin(x, ua[1]), ub[1]))
    return c.result(x * ua[1] / ub[1])
