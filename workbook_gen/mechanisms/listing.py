"""What ``workbook-gen list`` prints, without building the templates.

Building every template (its expression trees, the modules they need) takes most of
``list``'s time, though the listing only shows their names, parameters and outputs.
``_listing.py`` keeps the text as the templates last gave it, with a digest of the
sources that define them (this package's modules); ``listing()`` prints it while the
sources are unchanged and builds the templates otherwise (the same text, slower).
Refresh it after changing a template: ``python -m workbook_gen.mechanisms.listing``.
"""

from __future__ import annotations

import io
import zlib
from pathlib import Path

_HERE = Path(__file__).resolve().parent
_STORED = _HERE / "_listing.py"


def sources_digest() -> str:
    """A digest of the package's template sources (every module but the stored text)."""
    crc = 0
    for path in sorted(_HERE.glob("*.py")):
        if path.name != _STORED.name:
            crc = zlib.crc32(path.name.encode() + b"\x00" + path.read_bytes(), crc)
    return f"{crc:08x}"


def build_listing() -> str:
    """The listing from the templates themselves."""
    from . import TEMPLATES
    out = io.StringIO()
    for template in TEMPLATES.values():
        print(f"{template.id}: {template.title}", file=out)
        print(f"  {template.description}", file=out)
        spec = template.input
        print(f"  input: {spec.name} [{spec.unit}] {spec.description}, default "
              f"{spec.start:g}..{spec.stop:g} by {spec.step:g}", file=out)
        print("  parameters:", file=out)
        for p in template.parameters:
            print(f"    {p.name:<10} = {p.default:<12.10g} {p.unit:<6} {p.description}",
                  file=out)
        print("  outputs: " + ", ".join(q.header for q in template.quantities if q.output),
              file=out)
        for option in template.options:
            values = " | ".join(option.choices) if option.choices else type(
                option.default).__name__
            print(f"  option {option.name} = {option.default!r} ({values}): "
                  f"{option.description}", file=out)
        print(file=out)
    return out.getvalue()


def stored() -> tuple[str, str] | None:
    """(digest, text) kept in ``_listing.py``, None if there is none."""
    try:
        from . import _listing
    except ImportError:
        return None
    return _listing.DIGEST, _listing.TEXT


def listing() -> str:
    kept = stored()
    if kept is not None and kept[0] == sources_digest():
        return kept[1]
    return build_listing()


def refresh() -> Path:
    """Write ``_listing.py`` from the templates as they are now."""
    text = build_listing()
    _STORED.write_text(
        '"""What ``workbook-gen list`` prints (made by ``python -m '
        'workbook_gen.mechanisms.listing``;\nsee listing.py).  Do not edit."""\n\n'
        f"DIGEST = {sources_digest()!r}\n\nTEXT = {text!r}\n", encoding="utf-8")
    return _STORED


if __name__ == "__main__":
    print(refresh())
