"""workbook-gen: planar linkage kinematics as live-formula Excel workbooks, and their audit.

    from workbook_gen import load_scene, compute, write_workbook, audit
    scene = load_scene("templates/sewing_machine.toml", overrides={"l_BC": 105.0}, step=5.0)
    table = compute(scene)              # pandas DataFrame, columns exactly the Table headers
    path = write_workbook(scene, "outputs")
"""

from .errors import WorkbookGenError
from .version import VERSION as __version__

_LAZY = {"compute": ".tabulate", "load_scene": ".scene", "write_workbook": ".workbook"}


def __getattr__(name):
    """compute, load_scene and write_workbook on first use: ``audit`` needs none of
    them (pandas alone takes a second to import)."""
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def batch(scene, vary=None, design=None, out="outputs", jobs=None, client=None,
          summary_only=False, **options):
    """Design variants of ``scene``: one workbook each and a summary (a DataFrame)."""
    from .batching import batch as _batch
    return _batch(scene, vary, design, out, jobs, client, summary_only, **options)


def audit(path, **options):
    """Recompute and check every formula cell of the workbook at ``path``."""
    from .auditor import audit as _audit
    return _audit(path, **options)


__all__ = ["audit", "batch", "compute", "load_scene", "write_workbook", "WorkbookGenError", "__version__"]
