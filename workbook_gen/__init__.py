"""workbook-gen: planar linkage kinematics as live-formula Excel workbooks, and their audit.

    from workbook_gen import load_scene, compute, write_workbook, audit
    scene = load_scene("templates/sewing_machine.toml", overrides={"l_BC": 105.0}, step=5.0)
    table = compute(scene)              # pandas DataFrame, columns exactly the Table headers
    path = write_workbook(scene, "outputs")
"""

from .compute import compute
from .errors import WorkbookGenError
from .scene import load_scene
from .version import VERSION as __version__
from .workbook import write_workbook


def audit(path, **options):
    """Recompute and check every formula cell of the workbook at ``path``."""
    from .auditor import audit as _audit
    return _audit(path, **options)


__all__ = ["audit", "compute", "load_scene", "write_workbook", "WorkbookGenError", "__version__"]
