"""The unit of work of a batch: one variant in, (workbook bytes, summary row) out.

``run_variant`` is what ``workbook-gen generate SCENE --out DIR/<name>-batch --name
<name>-0001 --set ... --set ...`` does for that variant (the same scene parsing, the
same ``workbook_bytes``), without writing: the runners (this process, a process pool,
a Dask cluster) only schedule it and hand the bytes to the one writer in the parent.
It is pure: the same spec and variant give the same bytes and row anywhere.
"""

from __future__ import annotations

import logging
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence

from ..tabulate import evaluate
from ..errors import CannotAssembleError, SceneError
from ..scene import Scene, parse_scene
from ..workbook import workbook_bytes
from .rows import figure_values, summarise
from .variants import Variant

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class JobSpec:
    """What every variant of a batch shares: the scene file as read, the command's
    --set and --step, where the workbooks go, whether to audit them."""

    text: str                                  # the scene file's text
    source: str                                # its path, as given
    sets: tuple[tuple[str, object], ...] = ()  # --set NAME=VALUE, in order
    step: float | None = None                  # --step
    folder: str = "outputs"                    # DIR/<name>-batch, as the About sheet shows it
    stem: str = "scene"                        # the scene's name
    width: int = 4                             # digits of the file numbers
    audit: bool = False

    def file_stem(self, variant: Variant) -> str:
        return f"{self.stem}-{variant.index:0{self.width}d}"

    def file_name(self, variant: Variant) -> str:
        return f"{self.file_stem(variant)}.xlsx"

    def overrides(self, variant: Variant) -> dict[str, object]:
        """--set first, then the variant's values in --vary order."""
        return {**dict(self.sets), **dict(variant.values)}


@dataclass(frozen=True)
class Outcome:
    index: int
    data: bytes | None        # the workbook, None when refused
    row: dict[str, object]    # summary columns (not the varied parameters)


def variant_scene(spec: JobSpec, variant: Variant) -> Scene:
    """The variant's scene, exactly as ``generate`` would load it (SceneError if refused)."""
    return parse_scene(spec.text, spec.source, spec.overrides(variant), spec.step,
                       name=spec.file_stem(variant))


def refused_reason(spec: JobSpec, exc: SceneError) -> str:
    text = str(exc)
    prefix = f"{spec.source}: "
    return text[len(prefix):] if text.startswith(prefix) else text


def unassembled_reason(scene: Scene, parameters: Mapping[str, float] | None = None) -> str:
    """Why no row of the sweep assembles (the same text for every runner)."""
    sweep = scene.sweep
    failure = scene.template.assembly_failure(
        scene.parameters if parameters is None else parameters)
    return f"cannot be assembled anywhere in the sweep {sweep.start:g}..{sweep.stop:g}: {failure}"


def _audit(data: bytes, name: str) -> str:
    from ..auditor import audit
    fd, temp = tempfile.mkstemp(prefix=f".{name}.", suffix=".xlsx")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        return "ok" if audit(temp).ok else "fail"
    finally:
        Path(temp).unlink(missing_ok=True)


def run_variant(spec: JobSpec, variant: Variant) -> Outcome:
    """The variant's workbook and summary row; a refused variant has no workbook."""
    try:
        scene = variant_scene(spec, variant)
    except SceneError as exc:
        return Outcome(variant.index, None,
                       {"status": f"refused: {refused_reason(spec, exc)}", "file": ""})
    try:
        result = evaluate(scene)
    except CannotAssembleError:
        return Outcome(variant.index, None,
                       {"status": f"refused: {unassembled_reason(scene)}", "file": ""})
    name = spec.file_name(variant)
    data = workbook_bytes(scene, Path(spec.folder) / name, result)
    params = {k: [v] for k, v in result.params.items()}
    block = summarise(result.model, result.inputs, result.columns, result.status,
                      figure_values(result.model, params, 1), 1)
    row = {name: values[0] for name, values in block.items()}
    row["file"] = name
    row["audit"] = _audit(data, scene.name) if spec.audit else ""
    return Outcome(variant.index, data, row)


def run_chunk(spec: JobSpec, variants: Sequence[Variant]) -> list[Outcome]:
    """Several variants in one call: what a worker process or a Dask task runs."""
    return [run_variant(spec, v) for v in variants]
