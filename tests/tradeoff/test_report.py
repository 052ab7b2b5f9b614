"""tradeoff.report: the terminal table, its lines derived by hand for a small result
(Python's format mini-language: "{:.2e}", "{:,}",
https://docs.python.org/3/library/string.html#formatspec)."""

from __future__ import annotations

from types import SimpleNamespace

from workbook_gen.tradeoff.common import Row
from workbook_gen.tradeoff.measure import Tradeoff
from workbook_gen.tradeoff.report import format_table

SCENE = SimpleNamespace(name="demo", template=SimpleNamespace(id="slider_crank"))


def _result(rows, cpu=2.25):
    return Tradeoff(SCENE, rows, {}, 12.34, cpu)


def test_the_table_by_hand():
    rows = [Row("step", "10 deg", 1.234e-3, 0.5, 1234, 56789, cpu_seconds=0.25),
            Row("step", "1 deg", 2e-7, 12.345, 12345, 567890, note="fine"),
            Row("method", "n/a", None, None, None, None, note="closed form only")]
    text = format_table(_result(rows))
    lines = text.split("\n")
    assert lines[0] == "demo (slider_crank): speed against accuracy"
    assert lines[4] == ("dimension  setting  max error  seconds  CPU s   cells    bytes  note")
    assert lines[5] == "---------  -------  ---------  -------  -----  ------  -------"
    assert lines[6] == "step       10 deg    1.23e-03    0.500  0.250   1,234   56,789"
    assert lines[7] == "step       1 deg     2.00e-07     12.3      -  12,345  567,890  fine"
    assert lines[8] == ""  # a blank line between dimensions
    assert lines[9] == ("method     n/a              -        -      -       -        -  "
                        "closed form only")
    assert lines[-1] == "measured in 12.3 s (2.2 s CPU)"
    assert lines[-2] == ""


def test_no_cpu_time_no_parenthesis():
    text = format_table(_result([Row("precision", "float64", 1e-16, 0.001, 10, None)], cpu=None))
    assert text.endswith("\nmeasured in 12.3 s")
    assert "1.00e-16    0.001" in text
