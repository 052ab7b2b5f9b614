"""Batch: design variants of a scene, one auditable workbook each and a summary that
compares them (docs/batch.md).

    from workbook_gen import batch
    frame = batch("templates/sewing_machine.toml", vary={"l_BC": "95:105:5", "l_AB": [30, 32]})
    frame = batch("templates/four_bar.toml", vary={"branch": ["open", "crossed"],
                                                   "l_AB": [115, 120]})

Layers: ``specs`` (one varied parameter or option and its values), ``designfile``
(reading a CSV or xlsx design table), ``variants`` (which variants), ``job`` (the unit
of work: variant -> workbook bytes and summary row, the same code path as
``generate``), ``runners`` (this process, local processes, Dask), ``summary_only``
(all variants at once over numpy arrays), ``table``/``summary`` (summary.csv,
summary.xlsx), ``folder`` (resuming), ``api``.
"""

from .api import batch

__all__ = ["batch"]
