"""The hot-spot convergence study in `fe-crank check` (real mesh, solves and files):
`--convergence` on the small test throw, its results.json entry and its criterion."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.mesh import parse_mesh_section

pytestmark = pytest.mark.heavy  # three meshes of a small throw

DATA = Path(__file__).resolve().parents[1] / "data"


def test_mesh_section_convergence_key():
    assert parse_mesh_section({"size": "test", "convergence": True}, "c.toml").convergence is True
    assert parse_mesh_section({}, "c.toml").convergence is None
    with pytest.raises(InputError, match="mesh.convergence: must be true or false"):
        parse_mesh_section({"convergence": "yes"}, "c.toml")


def test_check_with_convergence_study(tmp_path, mesh_cache):
    out = tmp_path / "reports"
    code = main(
        [
            "check",
            str(DATA / "small_pass.toml"),
            "-o",
            str(out),
            "--mesh-size",
            "test",
            "--convergence",
            "--no-render",
            "--no-vtu",
            "--cache-dir",
            str(mesh_cache),  # the run's: the small throw's test mesh is the other tests' too
        ]
    )
    doc = json.loads((out / "small_pass" / "results.json").read_text())
    case = json.loads((out / "small_pass" / "case.json").read_text())
    from fe_crank.assess.results import load_schema

    jsonschema.validate(doc, load_schema())
    assert doc["support_model"].startswith("statically determinate")
    ((key, study),) = doc["mesh_convergence"].items()
    assert study["levels"] == [1.0, 1.5, 2.0]  # the test preset's r/1 times 1, 1.5, 2
    assert set(study["peaks"]) >= {"peak pin force"}
    for name, peaks in study["peaks"].items():
        assert study["changes"][name][-1] == pytest.approx(abs(peaks[2] - peaks[1]) / peaks[2])
    # the sign-off's criterion: the assessed mesh (the first level) against the finest
    assessed = {name: abs(p[-1] - p[0]) / p[-1] for name, p in study["peaks"].items()}
    assert study["assessed_changes"] == pytest.approx(assessed)
    crit = {c["name"]: c for c in doc["criteria"]}["mesh_convergence.max_peak_change"]
    assert crit["passed"] == study["converged"] == (max(assessed.values()) <= 0.05)
    assert crit["value"] == pytest.approx(max(assessed.values())) and crit["limit"] == 0.05
    # the stress criteria at the shaft fillets are taken at the study's estimate: the
    # group's own (assessed) safety divided by k >= the finest level's rise
    (throw,) = doc["throws"]
    groups = {g["group"]: g for g in throw["groups"]}
    rise = max(p[-1] / p[0] for name, p in study["peaks"].items() if "," not in name)
    static = {c["name"]: c for c in doc["criteria"]}["criteria.min_static_safety"]
    group = static["location"].split(", ")[1]
    assert group.startswith(("crankpin_fillet", "journal_fillet")) and "by the convergence study" in static["location"]
    k = float(static["location"].split("; x")[1].split(" ")[0])
    assert k >= max(1.0, rise) - 1e-3
    assert static["value"] * k == pytest.approx(groups[group]["static_safety"], rel=2e-3)
    assert [c["name"] for c in doc["criteria"]] == [c["name"] for c in case["criteria"]]
    assert code == (0 if all(c["passed"] for c in doc["criteria"]) else 1)
    assert doc["passed"] == (code == 0)
