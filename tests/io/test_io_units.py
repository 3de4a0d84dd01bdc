"""Units are parsed at the edge: explicit units, SI out, clear refusals."""

import math

import pytest

from fe_crank.io.units import to_si


@pytest.mark.parametrize(
    "text, kind, si",
    [
        ("66 mm", "length", 0.066),
        ("3000 rpm", "speed", 3000 * 2 * math.pi / 60),
        ("50 Hz", "speed", 100 * math.pi),
        ("293.07 rad/s", "speed", 293.07),
        ("5 MPa", "pressure", 5e6),
        ("2 bar", "pressure", 2e5),
        ("90 deg", "angle", math.pi / 2),
        ("0.62 kg", "mass", 0.62),
        ("7400 kg/m^3", "density", 7400.0),
        ("210 GPa", "pressure", 210e9),
    ],
)
def test_parses_to_si(text, kind, si):
    assert to_si(text, kind) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    "value, kind, words",
    [
        ("66 kg", "length", "is a mass, not a length"),
        (66, "length", "without a unit"),
        ("66", "length", "has no unit"),
        ("abc", "length", "cannot read"),
        ("3 m", "angle", "not an angle"),
        ("3000 N", "speed", "not a rotational speed"),
    ],
)
def test_refuses_bad_units(value, kind, words):
    with pytest.raises(ValueError, match=words):
        to_si(value, kind)


def test_a_repeated_text_gives_the_same_value_and_the_same_refusal():
    """The parse of a text is remembered: a second reading returns the same float (hand
    value 66 mm = 0.066 m), and a refused text is refused again with the same message
    (refusals are not remembered as values)."""
    assert to_si("66 mm", "length") == to_si("66 mm", "length") == pytest.approx(0.066, rel=1e-15)
    messages = []
    for _ in range(2):
        with pytest.raises(ValueError) as exc:
            to_si("66 kg", "length")
        messages.append(str(exc.value))
    assert messages[0] == messages[1] and "is a mass, not a length" in messages[0]
    with pytest.raises(ValueError, match="without a unit"):
        to_si(66, "length")
