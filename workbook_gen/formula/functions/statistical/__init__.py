"""Statistical (Excel's category, with its Compatibility names such as STDEV, NORMDIST):
aggregates, counts and the *IF(S) criteria (:mod:`.core`), fits, spread and quantiles
(:mod:`.fit`), shape statistics and hypothesis tests (:mod:`.testing`), continuous
distributions (:mod:`.distributions`), discrete ones (:mod:`.discrete`), least-squares
arrays (:mod:`.regress`).

Every function registered here has the family ``statistical``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.statistical import (  # noqa: F401  (each module registers)
    core, fit, testing, distributions, discrete, regress,
)
