"""The [torsion] section: units parsed at the edge, bad input refused with the file,
the key and the reason (exit 2 from the CLI, no traceback)."""

from __future__ import annotations

from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "loadcases" / "inline4_genset_torsion.toml"


def variant(tmp_path, old: str, new: str) -> Path:
    """The shipped case with one line changed, in a copy of the repository layout (the
    included geometry beside it, inside the case's folder tree as the path policy asks)."""
    text = CASE.read_text()
    assert old in text
    (tmp_path / "geometry").mkdir(exist_ok=True)
    for g in (ROOT / "geometry").glob("*.toml"):
        (tmp_path / "geometry" / g.name).write_text(g.read_text())
    (tmp_path / "loadcases").mkdir(exist_ok=True)
    p = tmp_path / "loadcases" / "case.toml"
    p.write_text(text.replace(old, new))
    return p


def test_shipped_case_parses_to_si():
    t = load_loadcase(CASE).torsion
    assert t.flywheel.inertia == pytest.approx(0.15)
    assert t.flywheel.stiffness == pytest.approx(4e5)
    assert t.cylinder_damping == pytest.approx(0.2)
    assert t.damper.damping == pytest.approx(3.0)
    assert t.speed_range[1] == pytest.approx(3600 * 3.141592653589793 / 30)
    assert [d.name for d in t.driven] == ["generator"]


def test_stiffness_in_kn_m_per_degree_is_converted(tmp_path):
    """1 kN m/deg = 1000 * 180 / pi N m/rad = 57295.78 N m/rad."""
    p = variant(tmp_path, 'stiffness = "4e5 N*m/rad"', 'stiffness = "1 kN*m/deg"')
    assert load_loadcase(p).torsion.flywheel.stiffness == pytest.approx(57295.7795, rel=1e-9)


@pytest.mark.parametrize(
    "old, new, key, reason",
    [
        ('inertia = "0.15 kg*m^2"', 'inertia = "-0.15 kg*m^2"', "torsion.flywheel.inertia", "inertia must be positive"),
        (
            'stiffness = "4e5 N*m/rad"',
            'stiffness = "-4e5 N*m/rad"',
            "torsion.flywheel.stiffness",
            "stiffness must be positive",
        ),
        ('stiffness = "4e5 N*m/rad"', 'stiffness = "4e5 N*m"', "torsion.flywheel.stiffness", "per angle"),
        (
            "shaft_loss_factor = 0.025",
            "shaft_loss_factor = 0.5",
            "torsion.shaft_loss_factor",
            "shaft_loss_factor must lie in [0, 0.2]",
        ),
        (
            "shaft_loss_factor = 0.025",
            "shaft_loss_factor = -0.01",
            "torsion.shaft_loss_factor",
            "shaft_loss_factor must lie",
        ),
        ("loss_factor = 0.3", "loss_factor = 1.5", "torsion.driven[0].loss_factor", "loss_factor must lie in [0, 1.0]"),
        (
            'cylinder_damping = "0.2 N*m*s/rad"',
            'cylinder_damping = "0.2 N*m*s"',
            "torsion.cylinder_damping",
            "per angle",
        ),
        (
            'stiffness = "8e3 N*m/rad"          # flexible rubber coupling',
            "",
            "torsion.driven[0]",
            "a driven machine needs the stiffness",
        ),
        (
            "shaft_loss_factor = 0.025          # dynamic magnifier 40, the low-damping end (docs/torsion.md)",
            "",
            "torsion.shaft_loss_factor",
            "required key is missing",
        ),
        (
            'speed_range = ["800 rpm", "3600 rpm"]',
            'speed_range = ["3600 rpm", "800 rpm"]',
            "torsion.speed_range",
            "increasing",
        ),
    ],
)
def test_bad_input_names_file_key_and_reason(tmp_path, old, new, key, reason):
    p = variant(tmp_path, old, new)
    with pytest.raises(InputError) as err:
        load_loadcase(p)
    assert err.value.file == str(p)
    assert err.value.key == key
    assert reason in str(err.value)


def test_no_damping_at_all_is_refused(tmp_path):
    p = variant(tmp_path, "shaft_loss_factor = 0.025", "shaft_loss_factor = 0.0")
    p.write_text(p.read_text().replace('cylinder_damping = "0.2 N*m*s/rad"', 'cylinder_damping = "0 N*m*s/rad"'))
    with pytest.raises(InputError, match="both zero"):
        load_loadcase(p)


def test_cli_exit_2_with_one_message_and_no_traceback(tmp_path, capsys):
    p = variant(tmp_path, 'inertia = "0.25 kg*m^2"', 'inertia = "-0.25 kg*m^2"')
    assert main(["torsion", str(p), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert str(p) in err and "torsion.driven[0]" in err and "inertia must be positive" in err
    assert "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_cli_refuses_a_case_without_torsion_section(tmp_path, capsys):
    case = ROOT / "loadcases" / "inline4_rated.toml"
    assert main(["torsion", str(case), "-o", str(tmp_path / "out")]) == 2
    assert "no [torsion] section" in capsys.readouterr().err
