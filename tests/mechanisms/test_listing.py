"""listing: the digest is the CRC-32 (zlib.crc32, ISO 3309) of the template sources in
name order, without the stored text; the stored text is used only while it matches;
refresh writes a module that reads back (exec) to the templates' own listing."""

from __future__ import annotations

import binascii
import re

import pytest

from workbook_gen.mechanisms import TEMPLATES, listing


@pytest.fixture(scope="module")
def built():
    return listing.build_listing()


def test_digest_is_crc32_of_names_and_bytes_in_order(tmp_path, monkeypatch):
    (tmp_path / "b.py").write_bytes(b"second\n")
    (tmp_path / "a.py").write_bytes(b"first\n")
    (tmp_path / "_listing.py").write_bytes(b"DIGEST = 'anything'\n")
    (tmp_path / "notes.txt").write_bytes(b"not a source")
    monkeypatch.setattr(listing, "_HERE", tmp_path)
    stream = b"a.py\x00first\nb.py\x00second\n"
    assert listing.sources_digest() == f"{binascii.crc32(stream):08x}"
    # the CRC-32 check value of "123456789" (ISO 3309 / ITU-T V.42) is cbf43926
    assert f"{binascii.crc32(b'123456789'):08x}" == "cbf43926"
    (tmp_path / "_listing.py").write_bytes(b"DIGEST = 'other'\n")  # excluded
    assert listing.sources_digest() == f"{binascii.crc32(stream):08x}"
    (tmp_path / "b.py").write_bytes(b"secone\n")
    assert listing.sources_digest() != f"{binascii.crc32(stream):08x}"


def test_the_stored_text_only_while_its_digest_matches(monkeypatch, built):
    monkeypatch.setattr(listing, "stored", lambda: (listing.sources_digest(), "kept text"))
    assert listing.listing() == "kept text"
    monkeypatch.setattr(listing, "stored", lambda: ("00000000", "stale text"))
    assert listing.listing() == built
    monkeypatch.setattr(listing, "stored", lambda: None)
    assert listing.listing() == built


def test_refresh_writes_a_module_that_reads_back(tmp_path, monkeypatch, built):
    monkeypatch.setattr(listing, "_STORED", tmp_path / "_listing.py")
    path = listing.refresh()
    assert path == tmp_path / "_listing.py"
    space: dict = {}
    exec(path.read_text(encoding="utf-8"), space)
    assert space["DIGEST"] == listing.sources_digest()
    assert space["TEXT"] == built


def test_the_listing_names_every_template_with_its_parameters(built):
    blocks = [b for b in built.split("\n\n") if b.strip()]
    assert [b.split(":")[0] for b in blocks] == list(TEMPLATES)
    for block, template in zip(blocks, TEMPLATES.values()):
        lines = block.splitlines()
        assert lines[0] == f"{template.id}: {template.title}"
        params = {}
        for line in lines:
            m = re.match(r"    (\S+)\s+= (\S+)", line)
            if m:
                params[m.group(1)] = float(m.group(2))
        assert params == pytest.approx(template.defaults, rel=1e-9, abs=0)
        outputs = next(x for x in lines if x.startswith("  outputs: "))
        assert outputs[len("  outputs: "):].split(", ") == [
            q.header for q in template.quantities if q.output]
