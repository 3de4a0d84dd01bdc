"""The small inline-4 of tests/data/small_shaft.toml with its counterweights bolted, for
the counterweight study's tests: every web's counterweight (the throws stay one solid,
one mesh) held by two radial M6 10.9 bolts through it into the web's end face."""

from __future__ import annotations

from pathlib import Path

from helpers.paths import DATA

BOLTED = (
    'bolted = { count = 2, diameter = "6 mm", pitch_radius = "30 mm", pitch = "1 mm", property_class = "10.9", '
    'clamp_length = "20 mm", bearing_diameter = "10 mm", hole_diameter = "6.6 mm", '
    'clamped_diameter = "12 mm", tightening_factor = 1.6 }'
)


def bolted_case(folder: Path, extra: str = "") -> Path:
    """tests/data/small_shaft.toml (``extra`` appended) on its geometry with the
    counterweights bolted (``BOLTED``), written into ``folder``."""
    text = (DATA / "geometry_small_shaft.toml").read_text()
    (folder / "geometry_small_shaft.toml").write_text(text.replace("webs = [1, 2]\n", f"webs = [1, 2]\n{BOLTED}\n", 1))
    (folder / "small_shaft.toml").write_text((DATA / "small_shaft.toml").read_text() + extra)
    return folder / "small_shaft.toml"


def torsion_section(speed_steps: int) -> str:
    """A ``[torsion]`` section for the small inline-4 (``bolted_case``'s ``extra``): a
    flywheel and a brake on the shaft's rear end, 2000-4800 rpm in ``speed_steps`` speeds."""
    return f"""
[torsion]
speed_range = ["2000 rpm", "4800 rpm"]
speed_steps = {speed_steps}
shaft_loss_factor = 0.025
cylinder_damping = "0.05 N*m*s/rad"

[torsion.flywheel]
inertia = "0.02 kg*m^2"
stiffness = "5e4 N*m/rad"

[[torsion.driven]]
name = "brake"
inertia = "0.01 kg*m^2"
stiffness = "2e3 N*m/rad"
loss_factor = 0.2
"""
