"""The user-facing contract lives in docs/ (issue 23 item 1), and the code keeps to it.

- Comments and docstrings cite docs/<doc>.md and a section heading that exists, never the
  specification outside this repository.
- Every scene key the scene loader accepts is in docs/scene.md (the keys are read off the
  loader's own refusals, not listed here); every option of every command's parser is in
  its doc; every field the audit's JSON holds (our workbooks audited, and a report with
  every optional part filled) is in docs/audit.md; every kind of summary.csv column a
  batch of each template writes is in docs/batch.md.
"""

from __future__ import annotations

import argparse
import ast
import dataclasses
import io
import re
import tokenize
from functools import lru_cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
SOURCES = ("workbook_gen", "bench", "scripts", "tests")

# A citation of the specification outside the repository: the word, then a section number,
# "section" or a possessive (cases in test_the_checker_catches_what_it_should).  Not the
# metavar NAME=SPEC, nor names such as SPEC_FORMS or SPECIAL.
SPEC_CITATION = re.compile(r"\bSPEC(?:'s\b|\s+(?:section\s+)?\d|\s+section\b)|\bsee SPEC\b")
DOC_CITATION = re.compile(r"docs/([\w.-]+\.md)(,\s*)?")


def _python_files() -> list[Path]:
    return sorted(p for folder in SOURCES for p in (ROOT / folder).rglob("*.py"))


@lru_cache(maxsize=None)
def _comments(path: Path) -> list[tuple[int, str]]:
    """(line, text) of every comment and docstring of a Python file."""
    source = path.read_text(encoding="utf-8")
    if "SPEC" not in source and "docs/" not in source:
        return []
    out = [(tok.start[0], tok.string)
           for tok in tokenize.generate_tokens(io.StringIO(source).readline)
           if tok.type == tokenize.COMMENT]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if (body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
                    and isinstance(body[0].value.value, str)):
                first = body[0].lineno
                out += [(first + i, line) for i, line in enumerate(body[0].value.value.split("\n"))]
    return out


@lru_cache(maxsize=None)
def _headings(doc: str) -> tuple[str, ...]:
    text = (DOCS / doc).read_text(encoding="utf-8")
    fenced = False
    found = []
    for line in text.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and re.match(r"#{1,6} ", line):
            found.append(line.lstrip("#").strip())
    return tuple(found)


def _doc_text(name: str) -> str:
    return (DOCS / name).read_text(encoding="utf-8")


def _named(text: str, word: str) -> bool:
    """``word`` in the doc as code: `word` (or inside a longer code span or block)."""
    return re.search(rf"(?<![\w-]){re.escape(word)}(?![\w-])", text) is not None


# -- citations --------------------------------------------------------------------------

def test_no_comment_cites_the_specification():
    found = [f"{path.relative_to(ROOT)}:{line}: {text.strip()}"
             for path in _python_files() for line, text in _comments(path)
             if SPEC_CITATION.search(text)]
    assert not found, "cite docs/<doc>.md, <Section> instead:\n" + "\n".join(found)


def test_doc_citations_name_a_doc_and_a_heading_that_exist():
    """A cited doc must exist, and a doc cited with a comma and a section must have a heading
    that the section starts with (on one line; a quoted heading without its quotes)."""
    bad = []
    for path in _python_files():
        for line, text in _comments(path):
            for m in DOC_CITATION.finditer(text):
                where = f"{path.relative_to(ROOT)}:{line}: {text.strip()}"
                doc = m.group(1)
                if not (DOCS / doc).is_file():
                    bad.append(f"{where}: no docs/{doc}")
                    continue
                if not m.group(2):
                    continue
                after = text[m.end():].lstrip('"')
                if not any(after.startswith(h) and not after[len(h):len(h) + 1].isalnum()
                           for h in _headings(doc)):
                    bad.append(f"{where}: docs/{doc} has no heading starting {after[:30]!r}")
    assert not bad, "\n".join(bad)


def test_links_between_docs_resolve():
    bad = [f"{doc.name}: {target}" for doc in DOCS.glob("*.md")
           for target in re.findall(r"\]\(([\w.-]+\.md)\)", doc.read_text(encoding="utf-8"))
           if not (DOCS / target).is_file()]
    assert not bad


def test_the_checker_catches_what_it_should():
    """The two patterns above, on lines they must and must not flag."""
    assert SPEC_CITATION.search("(SPEC 9.1, docs/stability.md)")
    assert SPEC_CITATION.search("see SPEC section 3")
    assert SPEC_CITATION.search("the SPEC's R")
    for fine in ('--vary NAME=SPEC', "SPEC_FORMS = 1", "_CSV_SPECIAL", "the command line's SPEC)"):
        assert not SPEC_CITATION.search(fine), fine
    assert "Summary" in _headings("workbook.md") and "Verdicts" in _headings("audit.md")


# -- scene keys -------------------------------------------------------------------------

def _refused_keys(toml: str) -> list[str]:
    """The keys a scene loader lists when it refuses an unknown one: "(a, b, c)"."""
    from workbook_gen.errors import SceneError
    from workbook_gen.scene import parse_scene
    with pytest.raises(SceneError) as caught:
        parse_scene(toml, "probe.toml")
    listed = re.search(r"is not an? [\w ]+ key \(([^)]*)\)", str(caught.value))
    assert listed, str(caught.value)
    return [k.strip() for k in listed.group(1).split(",")]


def test_every_scene_key_is_documented():
    from workbook_gen.mechanisms import TEMPLATES, get_template
    head = 'name = "x"\nmechanism = "four_bar"\n'
    top = _refused_keys(head + "zz_unknown = 1\n")
    sections = {
        "sweep": _refused_keys(head + "[sweep]\nzz_unknown = 1\n"),
        "outputs": _refused_keys(head + "[outputs]\nzz_unknown = 1\n"),
        "masses": _refused_keys(head + "[masses]\ncrank = { m = 1, u = 1, v = 1, zz_unknown = 1 }\n"),
    }
    assert {"name", "mechanism", "sweep", "masses"} <= set(top)
    text = _doc_text("scene.md")
    missing = [f"top-level {k}" for k in top if f"| `{k}` |" not in text]
    missing += [f"{section}.{k}" for section, keys in sections.items() for k in keys
                if f"| `{k}` |" not in text]
    for tid in TEMPLATES:
        template = get_template(tid)
        missing += [f"mechanism {tid}" for _ in [0] if f"`{tid}`" not in text]
        missing += [f"{tid} option {o.name}" for o in template.options
                    if f"| `{tid}` | `{o.name}` |" not in text]
        links = [link.name for link in template.links]
        if links:
            row = next((line for line in text.splitlines() if line.startswith(f"| `{tid}` | `")
                        and "`, `" in line and all(f"`{n}`" in line for n in links)), None)
            missing += [f"{tid} links {links}"] if row is None else []
    assert not missing, "docs/scene.md lacks: " + ", ".join(missing)


# -- command-line options ---------------------------------------------------------------

COMMAND_DOCS = {"list": "scene.md", "generate": "scene.md", "audit": "audit.md",
                "batch": "batch.md", "tradeoff": "tradeoff.md"}


def _commands() -> dict[str, argparse.ArgumentParser]:
    from workbook_gen.cli import parser
    top = parser()
    commands = {}
    for action in top._actions:
        if isinstance(getattr(action, "choices", None), dict):
            commands.update(action.choices)
    commands[""] = top
    return commands


def test_every_command_line_option_is_documented():
    commands = _commands()
    assert set(COMMAND_DOCS) == set(commands) - {""}, "a new command needs its doc"
    missing = []
    for name, sub in commands.items():
        doc = COMMAND_DOCS.get(name, "scene.md")
        text = _doc_text(doc)
        if name and f"workbook-gen {name}" not in text:
            missing.append(f"{doc}: workbook-gen {name}")
        for action in sub._actions:
            for option in action.option_strings:
                if option in ("-h", "--help"):
                    continue
                if not _named(text, option):
                    missing.append(f"{doc}: {name} {option}")
    assert not missing, "undocumented: " + ", ".join(missing)


# -- the audit's JSON -------------------------------------------------------------------

#: Objects whose keys are data (column, check or status names), not fields.
DATA_KEYED = {"reference", "residuals", "reference_problems", "flagged_rows"}


def _fields(value, out: set[str], parent: str = "") -> set[str]:
    if isinstance(value, dict):
        if parent in DATA_KEYED:
            return out
        for key, item in value.items():
            out.add(key)
            _fields(item, out, key)
    elif isinstance(value, list):
        for item in value:
            _fields(item, out, parent)
    return out


@pytest.fixture(scope="module")
def audited(tmp_path_factory):
    """The audit's JSON of two template workbooks (the sewing machine has the paper's
    table), and of one report with every optional part filled."""
    from workbook_gen.auditor import EngineResult, Mismatch, audit
    from workbook_gen.auditor.many import audit_file
    from workbook_gen.auditor.structure import Finding
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook
    out = tmp_path_factory.mktemp("audited")
    reports = [audit(write_workbook(load_scene(ROOT / "templates" / f"{name}.toml"), out))
               for name in ("sewing_machine", "four_bar")]
    full = Mismatch("Table!B2", "1+1", 3.0, 2.0, 1.0, root=False, area="B2:B3",
                    cells=["Table!B2"], at="Table!B3", sources=["Table!A2"],
                    followers=["Table!C2"], stale=True)
    filled = dataclasses.replace(
        reports[1], mismatches=[full], findings=[Finding("Table!B2", "error_value", "x")],
        not_checked={"Table!C2": "depends on Table!B2"}, by_contract={"Table!D2": "TODAY"},
        warnings={"overflow": 1},
        engine=EngineResult("libreoffice", 1, [full], 0, 0.1, differences=[full]))
    broken = out / "broken.xlsx"
    broken.write_text("not a zip")
    refused = audit_file(str(broken))
    assert refused.code == 2
    return [r.to_json() for r in reports] + [filled.to_json(), refused.json()]


def test_every_audit_json_field_is_documented(audited):
    fields = set()
    for report in audited:
        _fields(report, fields)
    assert {"ok", "mismatches", "paper_table", "engine", "followers"} <= fields
    text = _doc_text("audit.md")
    missing = sorted(f for f in fields if f"`{f}`" not in text)
    assert not missing, "docs/audit.md lacks the JSON fields: " + ", ".join(missing)


# -- summary.csv ------------------------------------------------------------------------

FIXED_COLUMNS = ("variant", "file", "status", "rows_flagged", "rows_not_assembled", "audit")
EXTREMES = re.compile(r"^(?P<q>\w+?)_(?P<kind>min_at|max_at|min|max)$")


@pytest.fixture(scope="module")
def summaries(tmp_path_factory):
    """summary.csv headers of a two-variant --summary-only batch of every scene in
    templates/ (a parameter varied; for four_bar an option too)."""
    from workbook_gen.batching.api import batch
    from workbook_gen.scene import load_scene
    out = tmp_path_factory.mktemp("summaries")
    found = []
    for path in sorted((ROOT / "templates").glob("*.toml")):
        scene = load_scene(path)
        first = next(iter(scene.parameters))
        value = scene.parameters[first]
        vary = {first: [value, value * 1.01]}
        options = [o for o in scene.template.options if o.choices]
        if options and path.stem == "four_bar":  # one template's option is enough
            vary[options[0].name] = list(options[0].choices[:2])
        frame = batch(path, vary=vary, out=out / path.stem, jobs=1, summary_only=True,
                      progress=False)
        header = (Path(frame.attrs["folder"]) / "summary.csv").read_text().splitlines()[0]
        found.append((scene, list(vary), header.split(",")))
    return found


def test_every_summary_column_kind_is_documented(summaries):
    text = _doc_text("batch.md")
    missing = set()
    for scene, varied, header in summaries:
        outputs = set(scene.template.outputs) | {q.name for q in scene.template.quantities}
        for column in header:
            name = re.sub(r" \[[^\]]*\]$", "", column)
            if name in FIXED_COLUMNS:
                kind = f"`{name}`"
            elif name in varied:
                option = name in {o.name for o in scene.template.options}
                kind = "each varied option" if option else "each varied parameter"
            elif (m := EXTREMES.match(name)) and m["q"] in outputs:
                kind = f"`<q>_{m['kind']}`"
            else:  # a span or a figure of the template
                kind = f"`{name}`"
            if kind not in text:
                missing.add(f"{kind} ({scene.mechanism})")
    assert not missing, "docs/batch.md lacks: " + ", ".join(sorted(missing))


# -- the docs' examples -----------------------------------------------------------------

#: The scenes behind docs/scene.md's error examples, by the file name the doc shows.
BAD_SCENES = {
    "e1.toml": 'name = "x"\nmechanism = "four_bar"\ncolour = 1\n',
    "e2.toml": 'name = "x"\nmechanism = "four_bar"\n[parameters]\nl_AB = -3\n',
    "e3.toml": 'name = "x"\nmechanism = "four_bar"\n[sweep]\nstep = 0\n',
    "e9.toml": 'name = "x"\nmechanism = "four_bar"\n[sweep]\nstart = 0\nstop = 10\nstep = 10\n',
    "e6.toml": 'name = "x"\nmechanism = "four_bar"\n[masses]\ncrank = { m = 1, u = 2 }\n',
    "e8.toml": 'name = "x"\nmechanism = "four_bar"\n[options]\nbalance = true\n',
}


def test_scene_examples_load_and_errors_read_as_documented():
    from workbook_gen.errors import SceneError
    from workbook_gen.scene import parse_scene
    text = _doc_text("scene.md")
    blocks = re.findall(r"```toml\n(.*?)```", text, re.S)
    assert len(blocks) == 2
    first = parse_scene(blocks[0], "first.toml")
    assert first.outputs == ("theta_3", "theta_4", "omega_4", "mu")
    masses = parse_scene('name = "m"\nmechanism = "four_bar"\n' + blocks[1], "m.toml")
    assert set(masses.masses) == {"crank", "coupler", "rocker"}
    shown = dict(re.findall(r"^workbook-gen: error: (e\d+\.toml): (.*)$", text, re.M))
    assert set(shown) == set(BAD_SCENES)
    for name, scene in BAD_SCENES.items():
        with pytest.raises(SceneError) as caught:
            parse_scene(scene, name)
        assert str(caught.value) == f"{name}: {shown[name]}"


def test_command_line_errors_read_as_documented(tmp_path, monkeypatch, capsys):
    """The one-line refusals docs/audit.md and docs/batch.md show are what the commands
    print (exit 2)."""
    from workbook_gen.cli import main
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook
    scene = str(ROOT / "templates" / "four_bar.toml")
    write_workbook(load_scene(scene), tmp_path)
    (tmp_path / "bad.xlsx").write_text("hi\n")
    monkeypatch.chdir(tmp_path)
    cases = [
        (["audit", "bad.xlsx"], "audit.md"),
        (["audit", "four_bar.xlsx", "--max-cells", "1000"], "audit.md"),
        (["batch", scene, "--vary", "l_AB=10:5:1"], "batch.md"),
        (["batch", scene, "--vary", "l_AB=normal:120:2", "--vary", "l_O2B=70,80",
          "--samples", "5"], "batch.md"),
    ]
    for argv, doc in cases:
        assert main(argv) == 2, argv
        said = capsys.readouterr().err.strip()
        assert said.startswith("workbook-gen: error: ") and said in _doc_text(doc), said
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.xlsx", "four_bar.xlsx"]
