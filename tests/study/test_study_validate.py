"""``fe-crank validate`` on a study file refuses what ``fe-crank study`` refuses, before
any meshing, with one message naming the file and the key; candidates that cannot be
built inside a valid range are counted, never refused."""

from __future__ import annotations

from pathlib import Path

import pytest
from helpers.bolted_study import bolted_case

from fe_crank.cli import main

CASE = Path(__file__).resolve().parents[1] / "data" / "small_shaft.toml"

BAD = [
    ("rotating_rate_percent = []", "study.rotating_rate_percent"),  # no candidate
    ("rotating_rate_percent = [50, 130]", "study.rotating_rate_percent[1]"),  # above 120 %
    ("rotating_rate_percent = [-5]", "study.rotating_rate_percent[0]"),
    (
        'rotating_rate_percent = [50]\n[study.limits]\nmax_counterweight_mass = "-1 kg"',
        "study.limits.max_counterweight_mass",
    ),
    ('rotating_rate_percent = [50]\nenvelope = "30 mm"', "study.envelope"),  # drawn r_outer 40 mm
    (  # rigid bearings: no film to judge
        'rotating_rate_percent = [50]\n[study.limits]\nmin_oil_film = "1 um"',
        "study.limits.min_oil_film",
    ),
    ('rotating_rate_percent = [50]\n[[study.placements]]\nname = "x"\nwebs = ["1.3"]', "study.placements[0].webs[0]"),
    ('rotating_rate_percent = [50]\n[[study.placements]]\nname = "x"\nwebs = ["1.1"]', "study.placements[0].webs"),
    (  # the overspeed screened with the stresses only
        'rotating_rate_percent = [50]\nstresses = "off"\n[study.limits]\nmin_overspeed_safety = 1.5',
        "study.limits.min_overspeed_safety",
    ),
    (
        "rotating_rate_percent = [50]\n[study.limits]\nmax_counterweight_overspeed_stress = 1.5",
        "study.limits.max_counterweight_overspeed_stress",
    ),
    # the bolted joints' VDI 2230 limits: plain numbers, the per-throw model, a bolted counterweight
    (
        'rotating_rate_percent = [50]\n[study.limits]\nmin_bolt_fatigue_safety = "1.2"',
        "study.limits.min_bolt_fatigue_safety",
    ),
    (
        'rotating_rate_percent = [50]\nstresses = "off"\n[study.limits]\nmax_bolt_assembly_utilisation = 0.9',
        "study.limits.max_bolt_assembly_utilisation",
    ),
    (  # small_shaft.toml's counterweights are not bolted
        "rotating_rate_percent = [50]\n[study.limits]\nmin_bolt_slip_safety = 1.8",
        "study.limits.min_bolt_slip_safety",
    ),
]


@pytest.mark.parametrize("body, key", BAD)
def test_validate_refuses_a_bad_study_with_file_and_key(tmp_path, capsys, body, key):
    f = tmp_path / "bad.toml"
    f.write_text("[study]\n" + body + "\n")
    rc = main(["validate", str(f), "--loadcase", str(CASE)])
    err = capsys.readouterr().err
    assert rc == 2
    assert str(f) in err and key in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_validate_counts_the_candidates_that_cannot_be_built(tmp_path, capsys):
    """120 % on four webs needs a 40 mm envelope's sector thicker than the 12 mm web:
    reported, and the file is valid (exit 0)."""
    f = tmp_path / "study.toml"
    f.write_text(
        '[study]\nrotating_rate_percent = [0, 120]\nenvelope = "40 mm"\nfree = ["thickness"]\n'
        '[[study.placements]]\nname = "4"\nwebs = ["1.1", "2.2", "3.1", "4.2"]\n'
    )
    rc = main(["validate", str(CASE), str(f)])  # the load case among the files
    out = capsys.readouterr().out
    assert rc == 0
    assert "2 candidates on" in out and "1 cannot be built (#1" in out


def test_validate_refuses_an_overspeed_limit_without_an_overspeed(tmp_path, capsys):
    """The load case states no overspeed: an overspeed limit cannot be judged."""
    text = CASE.read_text().replace('overspeed = "4800 rpm"\n', "")
    text = text.replace(
        'geometry = "geometry_small_shaft.toml"', f'geometry = "{CASE.parent / "geometry_small_shaft.toml"}"'
    )
    lc = tmp_path / "no_overspeed.toml"
    lc.write_text(text)
    f = tmp_path / "study.toml"
    f.write_text("[study]\nrotating_rate_percent = [50]\n[study.limits]\nmin_overspeed_safety = 1.5\n")
    rc = main(["validate", str(f), "--loadcase", str(lc), "--allow-outside-paths"])
    err = capsys.readouterr().err
    assert rc == 2
    assert str(f) in err and "study.limits.min_overspeed_safety" in err and "overspeed" in err
    assert len(err.strip().splitlines()) == 1


TORSION = """
[torsion]
speed_range = ["1000 rpm", "4000 rpm"]
speed_steps = 31
shaft_loss_factor = 0.025
cylinder_damping = "0.05 N*m*s/rad"

[torsion.flywheel]
inertia = "0.02 kg*m^2"
stiffness = "5e4 N*m/rad"
"""


def test_validate_takes_a_joint_limit_with_the_fe_throw_stiffness(tmp_path, capsys):
    """With [torsion] the check's joints take the torsional angular acceleration and the
    vibratory pin force of the candidate's own torsional stage, which the study runs with
    throw_stiffness = "fe" too (each candidate's FE throw stiffness): a joint limit is
    screened, not refused (the bolted shaft's study)."""
    lc = bolted_case(tmp_path, TORSION.replace("[torsion]\n", '[torsion]\nthrow_stiffness = "fe"\n'))
    assert 'throw_stiffness = "fe"' in lc.read_text()
    f = tmp_path / "study.toml"
    f.write_text("[study]\nrotating_rate_percent = [50]\n[study.limits]\nmin_bolt_slip_safety = 1.8\n")
    rc = main(["validate", str(f), "--loadcase", str(lc)])
    captured = capsys.readouterr()
    assert rc == 0, captured.err
    assert f"ok    {f}" in captured.out and "1 candidates" in captured.out
