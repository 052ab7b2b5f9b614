"""auditor/saved.py: ``dcterms:modified`` of docProps/core.xml as naive UTC.

References: the W3C date-time profile (https://www.w3.org/TR/NOTE-datetime: a zone
``+hh:mm`` is ahead of UTC), openpyxl writing the core properties of a workbook it saves,
and hand-written packages."""

from __future__ import annotations

import datetime as dt
import zipfile

import openpyxl

from workbook_gen.auditor import saved
from workbook_gen.auditor.saved import last_saved, parse_w3cdtf

CORE = ('<?xml version="1.0"?><cp:coreProperties xmlns:cp="http://schemas.openxmlformats.org/'
        'package/2006/metadata/core-properties" xmlns:dcterms="http://purl.org/dc/terms/" '
        'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"><dcterms:modified '
        'xsi:type="dcterms:W3CDTF">{when}</dcterms:modified></cp:coreProperties>')
RELS = ('<?xml version="1.0"?><Relationships xmlns="http://schemas.openxmlformats.org/package/'
        '2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/'
        'package/2006/relationships/metadata/core-properties" Target="{target}"/>'
        '</Relationships>')


def _package(path, parts: dict[str, str]):
    with zipfile.ZipFile(path, "w") as z:
        for name, text in parts.items():
            z.writestr(name, text)
    return path


def test_w3c_date_times_by_hand():
    assert parse_w3cdtf("2022-01-19T18:06:06Z") == dt.datetime(2022, 1, 19, 18, 6, 6)
    assert parse_w3cdtf("2022-01-19T18:06:06+02:00") == dt.datetime(2022, 1, 19, 16, 6, 6)
    assert parse_w3cdtf("2022-01-19T23:30-05:30") == dt.datetime(2022, 1, 20, 5, 0, 0)
    assert parse_w3cdtf(" 2022-01-19T18:06:06.123Z ") == dt.datetime(2022, 1, 19, 18, 6, 6)
    assert parse_w3cdtf("2022-01-19") == dt.datetime(2022, 1, 19)
    assert parse_w3cdtf("2022-02-30T00:00:00Z") is None     # no such day
    assert parse_w3cdtf("19/01/2022") is None
    assert parse_w3cdtf("") is None


def test_what_openpyxl_saved_is_read_back(tmp_path):
    openpyxl.Workbook().save(tmp_path / "a.xlsx")  # (openpyxl stamps the time of saving)
    stamped = openpyxl.load_workbook(tmp_path / "a.xlsx").properties.modified
    assert isinstance(stamped, dt.datetime)
    assert last_saved(tmp_path / "a.xlsx") == stamped.replace(tzinfo=None, microsecond=0)


def test_the_core_part_is_found_by_its_relationship(tmp_path):
    path = _package(tmp_path / "b.xlsx", {
        "_rels/.rels": RELS.format(target="/props/core2.xml"),
        "props/core2.xml": CORE.format(when="2020-06-01T12:00:00+01:00"),
        "docProps/core.xml": CORE.format(when="1999-01-01T00:00:00Z")})
    assert last_saved(path) == dt.datetime(2020, 6, 1, 11, 0, 0)
    no_rels = _package(tmp_path / "c.xlsx", {
        "docProps/core.xml": CORE.format(when="1999-01-01T00:00:00Z")})
    assert last_saved(no_rels) == dt.datetime(1999, 1, 1)


def test_a_file_that_does_not_say_or_says_it_badly_gives_none(tmp_path):
    assert last_saved(tmp_path / "missing.xlsx") is None
    (tmp_path / "text.xlsx").write_text("not a zip")
    assert last_saved(tmp_path / "text.xlsx") is None
    assert last_saved(_package(tmp_path / "d.xlsx", {"x.xml": "<a/>"})) is None
    assert last_saved(_package(tmp_path / "e.xlsx", {
        "docProps/core.xml": CORE.format(when="yesterday")})) is None
    assert last_saved(_package(tmp_path / "f.xlsx", {"docProps/core.xml": "<a><b"})) is None
    entity = '<?xml version="1.0"?><!DOCTYPE a [<!ENTITY x "y">]>' + CORE.format(
        when="2020-01-01T00:00:00Z")[len('<?xml version="1.0"?>'):]
    assert last_saved(_package(tmp_path / "g.xlsx", {"docProps/core.xml": entity})) is None
    big = CORE.format(when="2020-01-01T00:00:00Z") + " " * saved.MAX_PART
    assert last_saved(_package(tmp_path / "h.xlsx", {"docProps/core.xml": big})) is None
