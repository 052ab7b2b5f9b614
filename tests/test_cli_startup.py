"""Start-up (issue 9 item 12): ``--version`` and ``list`` import none of the heavy
libraries; a command imports what it uses.  A sys.modules check, not a timed test
(bench figures: python -X importtime, repeated runs)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

HEAVY = ("pandas", "xlsxwriter", "openpyxl", "numpy", "mpmath", "tqdm")

_PROBE = """
import contextlib, io, sys
from workbook_gen.cli import main
out = io.StringIO()
with contextlib.redirect_stdout(out):
    try:
        code = main({argv!r})
    except SystemExit as exc:  # --version exits through argparse
        code = exc.code
heavy = [m for m in {heavy!r} if m in sys.modules]
print(code, len(out.getvalue()), ",".join(heavy))
"""


def _run(argv: list[str]) -> tuple[int, int, list[str]]:
    code = _PROBE.format(argv=argv, heavy=HEAVY)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    return int(out[0]), int(out[1]), out[2].split(",") if len(out) > 2 else []


def test_list_imports_no_heavy_library():
    code, printed, heavy = _run(["list"])
    assert code == 0 and printed > 1000
    assert heavy == []


def test_version_imports_no_heavy_library_nor_the_templates():
    code, _, heavy = _run(["--version"])
    assert code == 0 and heavy == []
    probe = ("import sys\nfrom workbook_gen.cli import parser\n"
             "try:\n    parser().parse_args(['--version'])\nexcept SystemExit:\n    pass\n"
             "print(any(m.startswith('workbook_gen.mechanisms.') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True).stdout
    assert out.split()[-1] == "False"


def test_generate_imports_no_pandas_and_a_bad_scene_no_writer(tmp_path):
    """Writing a workbook needs XlsxWriter and numpy, not pandas; a scene refused while
    loading is refused before the writer is imported."""
    scene = tmp_path / "s.toml"
    scene.write_text((ROOT / "templates" / "sewing_machine.toml").read_text(encoding="utf-8"),
                     encoding="utf-8")
    code, _, heavy = _run(["generate", str(scene), "--out", str(tmp_path)])
    assert code == 0 and (tmp_path / "sewing_machine.xlsx").is_file()
    assert "pandas" not in heavy and "xlsxwriter" in heavy
    scene.write_text('mechanism = "loom"\n', encoding="utf-8")
    code, _, heavy = _run(["generate", str(scene), "--out", str(tmp_path / "no")])
    assert code == 2 and "xlsxwriter" not in heavy and "pandas" not in heavy


def test_importing_the_package_imports_no_heavy_library():
    probe = f"import sys, workbook_gen\nprint([m for m in {HEAVY!r} if m in sys.modules])"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_templates_load_on_demand_and_know_their_ids():
    from workbook_gen.mechanisms import TEMPLATES, get_template
    assert list(TEMPLATES)[:2] == ["slider_crank", "sewing_machine"]
    for template_id in TEMPLATES:
        assert get_template(template_id).id == template_id
    assert "nope" not in TEMPLATES


def test_public_compute_stays_the_function_after_the_package_is_imported_whole():
    """The README's ``from workbook_gen import compute`` gives the function, also once the
    writer (which imports the module computing the columns) has been imported: no submodule
    of that name may shadow it."""
    code = ("import workbook_gen.workbook, workbook_gen.tradeoff, workbook_gen.batching\n"
            "from workbook_gen import compute, load_scene\n"
            "table = compute(load_scene('templates/slider_crank.toml'))\n"
            "print(callable(compute), len(table))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["True", "37"]


def test_list_prints_the_stored_listing_without_building_a_template():
    """``list`` prints the text kept in mechanisms/_listing.py while the template sources
    are those it was made from (else it builds them: same text, slower)."""
    from workbook_gen.mechanisms import listing
    kept = listing.stored()
    assert kept is not None and kept[0] == listing.sources_digest(), (
        "mechanisms/_listing.py is stale: run python -m workbook_gen.mechanisms.listing")
    assert kept[1] == listing.build_listing()  # the templates' own text
    probe = ("import contextlib, io, sys\nfrom workbook_gen.cli import main\n"
             "out = io.StringIO()\nwith contextlib.redirect_stdout(out):\n    main(['list'])\n"
             "print(sorted(m for m in sys.modules if m.startswith('workbook_gen.mechanisms.')))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True).stdout
    assert out.split("\n")[-2] == "['workbook_gen.mechanisms._listing', " \
        "'workbook_gen.mechanisms.listing']"


def test_list_builds_the_templates_when_their_sources_changed(monkeypatch, capsys):
    from workbook_gen import cli
    from workbook_gen.mechanisms import listing
    monkeypatch.setattr(listing, "sources_digest", lambda: "changed")
    assert cli.main(["list"]) == 0
    assert capsys.readouterr().out == listing.build_listing()
