"""mechanisms/__init__.py: TEMPLATES, the templates by id, imported on first use, and
get_template. References: the ``mechanism =`` of every scene in templates/ (read here
with tomllib), each template's own ``id``, Python's Mapping protocol, and a fresh
interpreter's sys.modules for what importing the package loads."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from collections.abc import Mapping
from pathlib import Path

import pytest

from workbook_gen.errors import SceneError
from workbook_gen.mechanisms import TEMPLATES, get_template

ROOT = Path(__file__).resolve().parents[2]
SCENES = sorted(ROOT.glob("templates/*.toml"))


def test_every_scenes_mechanism_is_a_template():
    used = {tomllib.loads(p.read_text())["mechanism"] for p in SCENES}
    assert len(SCENES) >= 7
    assert used == set(TEMPLATES)       # each template has a scene, each scene a template


def test_a_mapping_of_ids_to_their_templates():
    assert isinstance(TEMPLATES, Mapping)
    assert len(TEMPLATES) == len(list(TEMPLATES)) == 7
    # in the order `workbook-gen list` printed them (the stored listing)
    from workbook_gen.mechanisms._listing import TEXT
    listed = [line.split(":")[0] for line in TEXT.splitlines()
              if line and not line.startswith(" ") and ":" in line]
    assert list(TEMPLATES) == listed
    for template_id in TEMPLATES:
        assert TEMPLATES[template_id].id == template_id
        assert template_id in TEMPLATES and get_template(template_id) is TEMPLATES[template_id]
    assert "nope" not in TEMPLATES and 3 not in TEMPLATES
    with pytest.raises(KeyError):
        TEMPLATES["nope"]
    assert TEMPLATES.get("nope") is None
    assert dict(TEMPLATES.items()).keys() == set(TEMPLATES)
    with pytest.raises(TypeError):
        TEMPLATES["x"] = None   # read-only


def test_an_unknown_id_is_a_scene_error_naming_the_known():
    with pytest.raises(SceneError) as err:
        get_template("four_bars")
    message = str(err.value)
    assert "'four_bars'" in message
    assert message.endswith(", ".join(sorted(TEMPLATES)))


def test_templates_are_imported_on_first_use():
    code = ("import sys\n"
            "from workbook_gen.mechanisms import TEMPLATES\n"
            "names = lambda: [m.rsplit('.', 1)[1] for m in sys.modules\n"
            "                 if m.startswith('workbook_gen.mechanisms.')]\n"
            "mods = lambda: sorted(n for n in names() if n in TEMPLATES)\n"
            "before = mods(); TEMPLATES['four_bar']; after = mods()\n"
            "print(before, after, 'four_bar' in TEMPLATES, len(TEMPLATES), mods())\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.strip()
    assert out == "[] ['four_bar'] True 7 ['four_bar']"
