"""The exceptions workbook-gen raises for things a caller can act on.

Every user-facing error derives from WorkbookGenError; the command line turns it
into a one-line message and exit code 2, never a traceback.
"""

from __future__ import annotations


class WorkbookGenError(Exception):
    """Base of every error a user can fix by changing their input."""


class SceneError(WorkbookGenError):
    """A scene file (or an override) is malformed: wrong type, unknown key, bad value."""


class IllegalNameError(SceneError):
    """A parameter or quantity name is not a legal Excel / LibreOffice defined name."""


class CannotAssembleError(SceneError):
    """The mechanism cannot be assembled anywhere in the sweep."""


class OutputExistsError(WorkbookGenError):
    """The output file exists and --force was not given."""


class OutputError(WorkbookGenError):
    """An output cannot be written where it was asked for: the folder cannot be written
    (permissions, a read-only file system), or the file's path is a folder."""


class FormulaSyntaxError(WorkbookGenError):
    """A formula's text does not parse."""


class UnsupportedFunctionError(WorkbookGenError):
    """A formula calls a function outside the supported list."""


class WorkbookReadError(WorkbookGenError):
    """An xlsx file is unusable: not a zip, broken or hostile XML, too large."""
