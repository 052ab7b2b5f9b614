"""Independent reference model: mechanism closure equations solved numerically.

``solve(mechanism, params, inputs)`` returns every output of a template as numpy arrays
(angles in degrees, rates in rad/s and rad/s^2, lengths in the scene's unit), computed by
batched Newton-Raphson on the loop-closure equations and linear solves of the
differentiated constraints. It shares no formula with the expressions that write the cells.
Rows that cannot be assembled are NaN throughout; rows at a singular position have NaN rates.
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

from workbook_gen.errors import WorkbookGenError

from . import (actuator_linkage, five_bar, four_bar, parallel_4dof, sewing_machine, slider_crank,
               walking_beam)

_MODULES = {"slider_crank": slider_crank, "sewing_machine": sewing_machine,
            "actuator_linkage": actuator_linkage,
            "five_bar": five_bar,
            "four_bar": four_bar, "walking_beam": walking_beam,
            "parallel_4dof": parallel_4dof}
MECHANISMS: tuple[str, ...] = tuple(_MODULES)


def _params(mechanism: str, params: Mapping[str, float]) -> dict[str, float]:
    module = _MODULES[mechanism]
    unknown = sorted(set(params) - set(module.DEFAULTS))
    if unknown:
        raise WorkbookGenError(f"{mechanism}: unknown parameter(s) {', '.join(unknown)}")
    merged = dict(module.DEFAULTS)
    for key, value in params.items():
        try:
            merged[key] = float(value)
        except (TypeError, ValueError):
            raise WorkbookGenError(f"{mechanism}: parameter {key} must be a number, got {value!r}") from None
        if not math.isfinite(merged[key]):
            raise WorkbookGenError(f"{mechanism}: parameter {key} must be finite, got {value!r}")
    for key in module.LENGTHS:
        if not merged[key] > 0.0:
            raise WorkbookGenError(f"{mechanism}: parameter {key} must be > 0, got {merged[key]!r}")
    return merged


# Templates tabulate their crank angle reduced to [-180, 180] (exact sines): the column's
# name and the parameter subtracted first (the slide direction of the slider-crank).
_REDUCED_INPUT = {"sewing_machine": ("theta_1r", None), "slider_crank": ("psi", "phi_slide"),
                  "four_bar": ("theta_2r", None), "walking_beam": ("theta_2r", None)}


def _reduced_deg(t: np.ndarray) -> np.ndarray:
    """t - 360 k in (-180, 180], with 180 kept (and -180 for -180)."""
    return np.where(np.abs(t) <= 180.0, t, t - 360.0 * np.ceil((t - 180.0) / 360.0))


def known_parameters(mechanism: str) -> frozenset[str]:
    """The parameter names the reference of ``mechanism`` takes."""
    return frozenset(_MODULES[mechanism].DEFAULTS)


def solve(mechanism: str, params: Mapping[str, float], inputs: np.ndarray,
          options: Mapping[str, object] | None = None) -> dict[str, np.ndarray]:
    """Outputs of ``mechanism`` at ``inputs`` (crank angles in deg, or the template's input);
    missing params take the defaults. ``options`` are the scene's template options
    (e.g. ``branch``); a module that takes none ignores them."""
    if mechanism not in _MODULES:
        raise WorkbookGenError(f"unknown mechanism {mechanism!r}; the reference supports {', '.join(MECHANISMS)}")
    p = _params(mechanism, params)
    theta_1 = np.atleast_1d(np.asarray(inputs, dtype=float))
    if theta_1.ndim != 1:
        raise WorkbookGenError(f"{mechanism}: inputs must be a 1-D array of angles, got shape {theta_1.shape}")
    module = _MODULES[mechanism]
    if getattr(module, "TAKES_OPTIONS", False):
        out = module.solve(p, theta_1, dict(options or {}))
    else:
        out = module.solve(p, theta_1)
    if mechanism in _REDUCED_INPUT:
        name, offset = _REDUCED_INPUT[mechanism]
        out[name] = _reduced_deg(theta_1 - (p[offset] if offset else 0.0))
    return out


__all__ = ["MECHANISMS", "known_parameters", "solve"]
