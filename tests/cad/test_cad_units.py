"""CAD route: the length unit a STEP or IGES file states, read from its text.

The STEP forms are those of ISO 10303-41 (an SI unit with a prefix; a conversion-based
unit sized by a measure in another unit); the IGES one is the global section's unit
flag (IGES 5.3, section 2.2.4.3).  The files are written here, as a CAD system writes
them (the header lines and entity numbers are arbitrary)."""

from __future__ import annotations

import pytest

from fe_crank.cad.units import AmbiguousUnit, iges_unit, step_unit

HEAD = "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n"
TAIL = "ENDSEC;\nEND-ISO-10303-21;\n"


def step(*lines: str) -> str:
    return HEAD + "\n".join(lines) + "\n" + TAIL


def test_si_units_with_and_without_prefix():
    mm = step("#10 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );")
    assert step_unit(mm).metres == pytest.approx(1e-3, rel=1e-15)
    m = step("#10=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.));")
    assert step_unit(m).metres == 1.0
    cm = step("#10 = ( LENGTH_UNIT()\n  NAMED_UNIT(*)\n  SI_UNIT(.CENTI.,.METRE.) );")  # split over lines
    assert step_unit(cm).metres == pytest.approx(1e-2, rel=1e-15)


def test_inch_as_a_conversion_based_unit_sized_in_millimetres():
    text = step(
        "#10 = ( CONVERSION_BASED_UNIT('INCH',#11) LENGTH_UNIT() NAMED_UNIT(#12) );",
        "#11 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#13);",
        "#12 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);",
        "#13 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
    )
    got = step_unit(text)  # the millimetre that sizes the inch is not a second unit
    assert got.name == "inch"
    assert got.metres == pytest.approx(0.0254, rel=1e-15)


def test_no_unit_and_two_different_units():
    assert step_unit(step("#1 = CARTESIAN_POINT('',(0.,0.,0.));")) is None
    two = step(
        "#10 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
        "#20 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );",
    )
    with pytest.raises(AmbiguousUnit):
        step_unit(two)


def _iges(flag: int, name: str) -> str:
    """An IGES start and global section (80 columns, section letter in column 73)."""
    glob = f"1H,,1H;,4HTEST,8Htest.igs,4HTEST,4HTEST,32,38,6,308,15,4HTEST,1.,{flag},{len(name)}H{name},1,0.01;"
    lines = ["test file".ljust(72) + "S0000001"]
    for i in range(0, len(glob), 72):
        lines.append(glob[i : i + 72].ljust(72) + f"G{i // 72 + 1:07d}")
    return "\n".join(lines) + "\n"


def test_iges_unit_flag():
    assert iges_unit(_iges(2, "MM")).metres == pytest.approx(1e-3, rel=1e-15)
    assert iges_unit(_iges(1, "INCH")).metres == pytest.approx(0.0254, rel=1e-15)
    assert iges_unit(_iges(6, "M")).metres == 1.0
    assert iges_unit(_iges(3, "CM")).metres == pytest.approx(1e-2, rel=1e-15)  # flag 3: the named unit
    assert iges_unit("no global section\n") is None
