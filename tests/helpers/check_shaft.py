"""The outputs of every stage of one load case as ``fe-crank check`` computes them
(``helpers.pipeline.stage_outputs``) with the whole-shaft stage's own output as that stage
returned it: its unit cases included, which the case's record drops once the assessment
has read them (``pipeline.stages.run_stages``).  A test that compares the whole shaft's
unit cases with another computation reads the check's own instead of solving the same
shaft again with the same calls."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fe_crank.assess.shaft import WholeShaftOutput
from fe_crank.outputs import CaseOutputs
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import Run, run_stages


class _ShaftKeepingRun(Run):
    """A run that also holds the whole-shaft stage's output as the stage returned it."""

    shaft: WholeShaftOutput | None = None

    def keep(self, **outputs: Any) -> None:
        ws = outputs.get("whole_shaft")
        if ws is not None and ws.cases is not None:
            self.shaft = ws
        super().keep(**outputs)


def stage_outputs_with_shaft(
    path: str | Path, cache_dir: str | Path, *, mesh_size: str = "test", **options: Any
) -> tuple[CaseOutputs, WholeShaftOutput | None]:
    """``helpers.pipeline.stage_outputs`` of ``path`` and the whole-shaft stage's output
    with its unit cases (None: no [shaft] model).  The whole fields are not drawn
    (``render`` and ``write_vtu`` off): drawing them drops the recovery fields the unit
    stresses are read from (``pipeline.shaft_stage.shaft_fields_stage``)."""
    options.setdefault("convergence", False)
    options.setdefault("render", False)
    options.setdefault("write_vtu", False)
    assert not (options["render"] or options["write_vtu"]), "the whole fields drop the unit cases' recovery fields"
    run = _ShaftKeepingRun(Path(path), CheckOptions(mesh_size=mesh_size, cache_dir=str(cache_dir), **options))
    run_stages(run)
    return run.out, run.shaft
