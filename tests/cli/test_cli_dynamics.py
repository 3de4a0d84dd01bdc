"""``fe-crank dynamics``: summary, JSON round trip against the library, plots, errors."""

import json

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.dynamics import analyse

CASE = "loadcases/single_cylinder.toml"


def test_dynamics_writes_json_and_plots(tmp_path, capsys, root):
    out = tmp_path / "out"
    rc = main(["dynamics", str(root / CASE), "-o", str(out), "--step", "2"])
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    assert "mean indicated torque" in cap.out
    data = json.loads((out / "dynamics.json").read_text())
    lc = load_loadcase(root / CASE)
    res = analyse(lc.engine, lc.operating, step=np.radians(2))
    assert data["summary"]["mean_torque"] == pytest.approx(res.mean_torque, rel=1e-12)
    assert data["summary"]["power"] == pytest.approx(res.power, rel=1e-12)
    assert len(data["theta"]) == 360
    np.testing.assert_allclose(data["torque"], res.torque, rtol=1e-5, atol=1e-6 * np.abs(res.torque).max())
    np.testing.assert_allclose(data["throws"]["1"]["pin_force_y"], res.throws["1"].pin_force[:, 1], rtol=1e-5)
    np.testing.assert_allclose(data["cylinders"]["1"]["s"], res.cylinders["1"].motion.s, rtol=1e-5, atol=1e-12)
    assert f"{res.mean_torque:.2f}" in cap.out
    for name in ("piston_motion.png", "forces.png", "torque.png", "crankpin_polar.png"):
        blob = (out / name).read_bytes()
        assert blob[:8] == b"\x89PNG\r\n\x1a\n" and len(blob) > 5000
    # nothing half-written left behind
    assert not [p for p in out.iterdir() if p.name.startswith(".")]


def test_dynamics_bad_input_exits_2_without_traceback(tmp_path, capsys, root):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\nengine = "missing.toml"\n[operating]\nspeed = "2800 rpm"\n')
    assert main(["dynamics", str(bad), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "missing.toml" in err and "Traceback" not in err
    assert main(["dynamics", str(root / CASE), "-o", str(tmp_path / "o"), "--step", "0"]) == 2
    err = capsys.readouterr().err
    assert "--step" in err and "Traceback" not in err
