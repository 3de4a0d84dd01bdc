"""``fe-crank balance``: outputs of a load case and an engine file; bad input exits 2."""

import json
from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.io.loadcase import load_loadcase

ENGINES = Path(__file__).resolve().parents[2] / "engines"

CASE = """
name = "V4-90 pneumatic, seed 003 counterweights"
engine = "{engine}"

[operating]
speed = "3000 rpm"

[balance]
reference_z = "0 mm"
reciprocating_fraction = 0.5
couple = "whole_shaft"
planes = ["-108.5 mm", "-64 mm", "64 mm", "108.5 mm"]

[balance.counterweight]
density = "7400 kg/m^3"
free = "thickness"
r_outer = "71 mm"
r_inner = "32 mm"
angle = "180 deg"
envelope = "{envelope}"
journal_radius = "25 mm"

[[balance.shafts]]
component = "force"
order = 2
offset = "80 mm"
"""


def write_case(tmp_path, envelope="75 mm", extra=""):
    p = tmp_path / "case.toml"
    # the engine beside the case: include paths stay in the load case's folder tree
    (tmp_path / "engine.toml").write_bytes((ENGINES / "v4_90_pneumatic.toml").read_bytes())
    p.write_text(CASE.format(engine="engine.toml", envelope=envelope) + extra)
    return p


def test_load_case_section_is_parsed(tmp_path):
    lc = load_loadcase(write_case(tmp_path))
    assert lc.balance.strategy.couple == "whole_shaft"
    assert lc.balance.strategy.planes == pytest.approx((-0.1085, -0.064, 0.064, 0.1085))
    assert lc.balance.counterweight.density == 7400.0 and lc.balance.shafts[0].order == 2


def test_balance_of_a_load_case_writes_json_and_hodographs(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["balance", str(write_case(tmp_path)), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "counterweights" in text and "residual" in text
    data = json.loads((out / "balance.json").read_text())
    cws = data["counterweights"]
    assert len(cws) == 4
    for cw in cws:  # seed 003: 0.887 kg sector at 34 mm, 19 mm thick (here solved for the exact need)
        assert cw["sector"]["thickness_mm"] == pytest.approx(18.8, abs=0.1)
        assert cw["sector"]["centroid_radius_mm"] == pytest.approx(34.35, abs=0.01)
    assert data["balance_shafts"][0]["shafts"][0]["speed_ratio"] in (2, -2)
    residual = {r["order"]: r for r in data["residual"]}
    assert residual[1.0]["force"]["kind"] == "zero" and residual[1.0]["moment"]["kind"] == "zero"
    assert residual[2.0]["force"]["kind"] == "zero"  # taken by the balance shafts
    for k in (1, 2):
        png = out / f"hodograph_order{k}.png"
        assert png.exists() and png.read_bytes()[:4] == b"\x89PNG"


def test_balance_of_an_engine_file(tmp_path):
    out = tmp_path / "o"
    assert main(["balance", str(ENGINES / "inline4.toml"), "--speed", "3000 rpm", "-o", str(out), "--no-plots"]) == 0
    data = json.loads((out / "balance.json").read_text())
    second = next(r for r in data["free_forces"]["reciprocating"] if r["order"] == 2.0)
    assert second["force"]["kind"] == "line"
    assert not list(out.glob("*.png"))


def check_error(argv, capsys, *words):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and err.count("\n") == 1
    for w in words:
        assert w in err
    return err


def test_counterweight_that_cannot_fit_exits_2(tmp_path, capsys):
    case = write_case(tmp_path, envelope="75 mm").read_text().replace('free = "thickness"', 'free = "r_outer"')
    case = case.replace('r_outer = "71 mm"\n', 'thickness = "5 mm"\n')
    p = tmp_path / "tight.toml"
    p.write_text(case)
    check_error(["balance", str(p)], capsys, "envelope", "balance.counterweight")


def test_negative_fraction_exits_2(tmp_path, capsys):
    p = tmp_path / "neg.toml"
    p.write_text(
        write_case(tmp_path).read_text().replace("reciprocating_fraction = 0.5", "reciprocating_fraction = -0.5")
    )
    check_error(["balance", str(p)], capsys, "reciprocating_fraction", str(p))
    check_error(
        ["balance", str(ENGINES / "inline4.toml"), "--speed", "3000 rpm", "--fraction", "-0.2"],
        capsys,
        "reciprocating_fraction",
    )


def test_empty_engine_exits_2(tmp_path, capsys):
    p = tmp_path / "empty.toml"
    p.write_text('name = "empty"\nstrokes = 4\ncylinders = []\n[[throws]]\nname = "1"\nstroke = "80 mm"\n')
    check_error(["balance", str(p), "--speed", "3000 rpm"], capsys, "cylinders")


def test_shaft_with_no_cylinders_exits_2(tmp_path, capsys):
    text = (ENGINES / "inline4.toml").read_text()
    p = tmp_path / "idle.toml"
    p.write_text(text + '\n[[shafts]]\nname = "main"\n\n[[shafts]]\nname = "idler"\n')
    check_error(["balance", str(p), "--speed", "3000 rpm"], capsys, "idler", str(p))


def test_engine_file_needs_a_speed_with_a_unit(capsys):
    check_error(["balance", str(ENGINES / "inline4.toml")], capsys, "--speed")
    check_error(["balance", str(ENGINES / "inline4.toml"), "--speed", "3000"], capsys, "--speed")
