"""Independent cross-check: the time-domain sum of the exact inertia forces of all cylinders,
from the mechanism stage's ``fe_crank.mechanism.kinematics.piston_motion`` at the crank angles of
``fe_crank.mechanism.dynamics.cylinder_angle``, against the balance stage's sum over orders; and the
order-k coefficients against the discrete Fourier transform of that time signal."""

import dataclasses
import math

import numpy as np
import pytest
from helpers.balance import engine, radial

from fe_crank.balance import free_forces
from fe_crank.balance.mechanism import reciprocating_mass
from fe_crank.mechanism.dynamics import cylinder_angle
from fe_crank.mechanism.kinematics import piston_motion

W = 250.0
N = 720


def time_signal(e, theta):
    """Force (n, 2) and moment about the origin (n, 3) of the reciprocating masses."""
    f = np.zeros((theta.size, 2))
    m = np.zeros((theta.size, 3))
    for c in e.cylinders:
        t = e.throw(c.throw)
        sh = e.shaft(t.shaft)
        phi = cylinder_angle(e, c, theta)
        mo = piston_motion(phi, t.crank_radius, c.rod.length, sh.speed_ratio * W, offset=c.pin_offset)
        axis = np.array([math.sin(c.bank_angle), math.cos(c.bank_angle)])
        normal = sh.sense * np.array([math.cos(c.bank_angle), -math.sin(c.bank_angle)])
        fc = reciprocating_mass(c) * mo.a[:, None] * axis  # a > 0 towards the axis: inertia force outwards
        px, py = np.array(sh.centre) + c.pin_offset * normal
        z = t.axial_position
        f += fc
        m += np.stack([-z * fc[:, 1], z * fc[:, 0], px * fc[:, 1] - py * fc[:, 0]], axis=1)
    return f, m


def offset_inline4():
    e = engine("inline4.toml")
    cyls = tuple(dataclasses.replace(c, pin_offset=0.004) for c in e.cylinders)
    return dataclasses.replace(e, cylinders=cyls, name="inline-4 with 4 mm pin offset")


CASES = {
    "v8_crossplane": lambda: engine("v8_crossplane.toml"),
    "deltic": lambda: engine("napier_deltic_section.toml"),
    "v4_pneumatic": lambda: engine("v4_90_pneumatic.toml"),
    "inline4_offset": offset_inline4,
    "radial5": lambda: radial(5, piston=3.0),
}


@pytest.mark.parametrize("name", list(CASES))
def test_sum_over_orders_equals_time_domain_sum(name):
    e = CASES[name]()
    th = 2 * np.pi * np.arange(N) / N
    f_ref, m_ref = time_signal(e, th)
    ff = free_forces(e, W)
    f, m = ff.evaluate(th, sources=("reciprocating",))
    scale = np.abs(f_ref).max() + sum(reciprocating_mass(c) for c in e.cylinders) * 0.05 * W**2
    assert np.abs(f - f_ref).max() < 1e-9 * scale
    assert np.abs(m - m_ref).max() < 1e-9 * scale * 2.0
    # truncated to orders 1, 2, 4, 6 (odd ones too with an offset pin) the error is the truncation
    orders = (1, 2, 3, 4, 5, 6) if name == "inline4_offset" else (1, 2, 4, 6)
    f6, _ = ff.evaluate(th, sources=("reciprocating",), orders=orders)
    assert np.abs(f6 - f_ref).max() < 1e-3 * scale


@pytest.mark.parametrize("name", list(CASES))
def test_order_coefficients_equal_the_fft_of_the_time_signal(name):
    e = CASES[name]()
    th = 2 * np.pi * np.arange(N) / N
    f_ref, m_ref = time_signal(e, th)
    spec_f = np.fft.rfft(f_ref, axis=0) / N
    spec_m = np.fft.rfft(m_ref, axis=0) / N
    ff = free_forces(e, W)
    scale = np.abs(f_ref).max()
    for k in range(1, 9):
        t = ff.term("reciprocating", k)
        got = t.force[:, 0] - 1j * t.force[:, 1]  # a cos + b sin  <->  2 X_k = a - i b
        assert np.abs(got - 2 * spec_f[k]).max() < 1e-9 * scale, k
        gotm = t.moment[:, 0] - 1j * t.moment[:, 1]
        assert np.abs(gotm - 2 * spec_m[k]).max() < 1e-9 * scale, k


def test_articulated_rod_differs_from_plain_and_matches_finite_differences():
    """Master/articulated rods: the link pin does not circle the crank axis, so the articulated
    pistons' harmonics differ from the plain slider crank; check them against a direct
    geometric construction differentiated by central differences."""
    plain, art = radial(5, piston=3.0), radial(5, piston=3.0, link_radius=0.05)
    fp = free_forces(plain, W).term("reciprocating", 2).force_hodograph()
    fa = free_forces(art, W).term("reciprocating", 2).force_hodograph()
    first = free_forces(art, W).term("reciprocating", 1).force_hodograph().major
    assert fp.kind == "zero" and fa.major > 0.05 * first  # second order no longer cancels

    def positions(th):
        r, l = 0.1, 0.4
        crank = r * np.stack([np.sin(th), np.cos(th)], 1)
        xm = crank[:, 1] + np.sqrt(l**2 - crank[:, 0] ** 2)  # master on +y
        gamma = np.arctan2(-crank[:, 0], xm - crank[:, 1])  # master rod direction
        out = [xm]
        for j in range(1, 5):
            b = 2 * np.pi * j / 5
            link = crank + 0.05 * np.stack([np.sin(gamma + b), np.cos(gamma + b)], 1)
            e_ = np.array([np.sin(b), np.cos(b)])
            n_ = np.array([np.cos(b), -np.sin(b)])
            out.append(link @ e_ + np.sqrt((l - 0.05) ** 2 - (link @ n_) ** 2))
        return np.array(out)

    th = np.linspace(0, 2 * np.pi, 97)
    h = 1e-4
    acc = (positions(th + h) - 2 * positions(th) + positions(th - h)) / h**2 * W**2
    f = np.zeros((th.size, 2))
    for j in range(5):
        b = 2 * np.pi * j / 5
        f += -3.0 * acc[j][:, None] * np.array([np.sin(b), np.cos(b)])
    got, _ = free_forces(art, W).evaluate(th, sources=("reciprocating",))
    assert np.abs(got - f).max() < 1e-5 * np.abs(f).max()


@pytest.mark.parametrize("name", ["v8_crossplane", "deltic"])
def test_dynamics_stage_inertia_forces_sum_to_the_free_reciprocating_force(name):
    """The dynamics stage's per-cylinder inertia force (``-m_j a``, positive towards the crank
    axis) summed along the cylinder axes over its own cycle grid."""
    from fe_crank import model
    from fe_crank.mechanism.dynamics import analyse

    e = CASES[name]()
    res = analyse(e, model.OperatingPoint(W))
    f_ref = np.zeros((res.theta.size, 2))
    for c in e.cylinders:
        axis = np.array([math.sin(c.bank_angle), math.cos(c.bank_angle)])
        f_ref += -res.cylinders[c.name].inertia[:, None] * axis
    f, _ = free_forces(e, W).evaluate(res.theta, sources=("reciprocating",))
    assert np.abs(f - f_ref).max() < 1e-9 * np.abs(f_ref).max()
