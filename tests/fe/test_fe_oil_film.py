"""The short-bearing oil film (fe_crank.fe.oil_film) against closed forms and an independent integration.

Every reference here is written in the test: Ocvirk's steady-load relations, the
pure-squeeze approach time (derived by hand below, and checked against a quadrature of
its defining integral), the half-Sommerfeld force by numerical quadrature, and the
periodic orbit by scipy's solve_ivp on that quadrature force.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from fe_crank.fe.oil_film import (
    JournalBearing,
    film_force,
    finite_factor,
    mobility,
    peak_pressure_factor,
    periodic_orbits,
)
from fe_crank.geometry.oil import walther_viscosity


def quad_force(eps, u):
    """F / k0 of the half-Sommerfeld short bearing by quadrature: int (u.n)_+ n / (1 - eps.n)^3."""
    eps, u = np.asarray(eps, float), np.asarray(u, float)

    def f(a, k):
        n = np.array([math.cos(a), math.sin(a)])
        return max(float(u @ n), 0.0) * n[k] / (1.0 - float(eps @ n)) ** 3

    brk = [math.atan2(u[1], u[0]) + s * math.pi / 2 for s in (-1, 1)]
    return np.array([quad(f, -np.pi, np.pi, args=(k,), points=brk, limit=400, epsabs=1e-13)[0] for k in range(2)])


@pytest.mark.parametrize("seed", range(4))
def test_closed_form_force_matches_quadrature(seed):
    rng = np.random.default_rng(seed)
    eps = rng.uniform(-0.65, 0.65, 2)
    u = rng.normal(size=2)
    assert np.allclose(film_force(eps, u), quad_force(eps, u), rtol=1e-9, atol=1e-9)


def ocvirk_load(eps):
    """Ocvirk's steady short-bearing load over k0 omega (k0 = mu R B^3 / c^2):
    W = mu U B^3 / (4 c^2) eps / (1 - eps^2)^2 sqrt(16 eps^2 + pi^2 (1 - eps^2)), U = R omega."""
    return eps / (1 - eps**2) ** 2 * math.sqrt(16 * eps**2 + math.pi**2 * (1 - eps**2)) / 4


@pytest.mark.parametrize("eps", [0.2, 0.5, 0.8, 0.95, 0.995])  # 0.995: from the centre under W / (k0 omega) = 1e4
def test_steady_load_eccentricity_and_attitude_angle(eps):
    """A constant load: the orbit settles at Ocvirk's eccentricity, at the attitude angle
    tan(phi) = pi sqrt(1 - eps^2) / (4 eps) from the load line, in the direction of rotation."""
    w = ocvirk_load(eps)
    o = periodic_orbits(np.tile([0.0, -w], (1, 90, 1)), 2.0)
    assert o.converged.all()
    e = o.eps[0, -1]
    assert np.hypot(*e) == pytest.approx(eps, abs=1e-6)
    attitude = math.atan2(e[0], -e[1])  # from -y (the load) towards +x (the journal turns +x -> +y)
    assert attitude == pytest.approx(math.atan(math.pi * math.sqrt(1 - eps**2) / (4 * eps)), abs=1e-6)
    # the mobility: under this load at this eccentricity the squeeze velocity is -omega/2 e_z x eps
    m = mobility(e, np.array([0.0, -1.0])) * w
    assert np.allclose(m, [0.5 * e[1], -0.5 * e[0]], atol=1e-9)


def squeeze_time(e0, e1):
    """Pure squeeze along the load line, no rotation: k0 I(eps) d eps/dt = W with
    I = int_{-pi/2}^{pi/2} cos^2 / (1 - eps cos)^3 = [(1 + 2 eps^2)(pi/2 + asin eps) + 3 eps sqrt(1 - eps^2)]
    / (1 - eps^2)^(5/2) = d/d eps [eps (pi/2 + asin eps) / (1 - eps^2)^(3/2) + 1 / (1 - eps^2)],
    so t W / k0 = G(e1) - G(e0)."""

    def G(e):
        return e * (math.pi / 2 + math.asin(e)) / (1 - e * e) ** 1.5 + 1 / (1 - e * e)

    return G(e1) - G(e0)


def test_squeeze_closed_form_is_the_integral():
    for e in (0.1, 0.5, 0.9):
        integral = quad(lambda p, e=e: math.cos(p) ** 2 / (1 - e * math.cos(p)) ** 3, -np.pi / 2, np.pi / 2)[0]
        h = 1e-6
        assert (squeeze_time(e - h, e + h) / (2 * h)) == pytest.approx(integral, rel=1e-7)


def _radius_crossing(r, times, target):
    """The time |eps| reaches ``target`` (linear between samples)."""
    k = int(np.argmax(r >= target))
    return times[k - 1] + (target - r[k - 1]) / (r[k] - r[k - 1]) * (times[k] - times[k - 1])


def test_pure_squeeze_approach_time():
    """Constant load, no rotation: the time from eps 0.2 to 0.8 is the closed form's."""
    w = 2.0  # W / (k0 omega); omega only scales time here (0.2 -> 0.8 within the cycle)
    n, turns = 1000, 1.0
    tau = 2 * np.pi * turns * np.arange(1, n + 1) / n
    load = np.tile([0.0, -w], (1, n, 1))
    o = periodic_orbits(load, turns, mean_speed=0.0, max_cycles=1, substeps=4, start=np.array([[0.0, -0.2]]))
    r = np.roll(np.hypot(o.eps[0, :, 0], o.eps[0, :, 1]), -1)  # o.eps[i]: at angle i (i = 0: the cycle's end)
    t = _radius_crossing(r, tau, 0.8)
    assert t == pytest.approx(squeeze_time(0.2, 0.8) / w, rel=2e-4)
    assert np.allclose(o.eps[0, :, 0], 0.0, atol=1e-12)  # along the load line


def test_load_rotating_at_half_speed_is_not_carried():
    """A load rotating with the journal's mean speed omega/2: seen from a frame turning with
    it the film is in pure squeeze under a steady load, so the journal runs out towards the
    clearance circle along the pure-squeeze law and never settles."""
    w = 2.0  # 0.2 -> 0.8 within the cycle
    n, turns = 1000, 2.0  # the load turns once per cycle
    tau = 2 * np.pi * turns * np.arange(n) / n
    load = w * np.stack([np.sin(0.5 * tau), -np.cos(0.5 * tau)], axis=-1)[None]  # from -y towards +x
    start = np.array([[0.0, -0.2]])  # on the load line
    o = periodic_orbits(load, turns, max_cycles=1, substeps=4, start=start)
    r = np.roll(np.hypot(o.eps[0, :, 0], o.eps[0, :, 1]), -1)
    times = tau + tau[1]
    assert np.all(np.diff(r) > 0)  # always running out
    assert _radius_crossing(r, times, 0.8) == pytest.approx(squeeze_time(0.2, 0.8) / w, rel=2e-4)
    # and the journal stays on the load line as it turns
    e = np.roll(o.eps[0], -1, axis=0)
    assert np.allclose(
        np.arctan2(e[:, 0], -e[:, 1]), np.angle(np.exp(0.5j * times)), atol=5e-5
    )  # the steps lag by 2.5e-5 rad
    # no periodic orbit: it runs on towards the clearance circle, still by the squeeze law
    o2 = periodic_orbits(load[:, ::4], turns, max_cycles=3, substeps=2, start=start)
    assert not o2.converged[0]
    e_end = float(np.hypot(*o2.eps[0, 0]))  # the end of the third cycle
    assert squeeze_time(0.2, e_end) == pytest.approx(w * 3 * 2 * np.pi * turns, rel=1e-3)


def _load_history(theta):
    """A main-bearing-like load over a four-stroke cycle (W / (k0 omega), periodic in 4 pi):
    a steady part, half, first and second orders and a firing peak."""
    fx = 0.6 * np.cos(theta / 2) + 0.8 * np.cos(theta) + 0.2 * np.sin(2 * theta)
    peak = sum(np.exp(-(((theta - 0.3 - k * 4 * np.pi) / 0.6) ** 2)) for k in (-1, 0, 1))
    fy = -1.0 + 0.9 * np.sin(theta) + 0.3 * np.cos(2 * theta) - 3.0 * peak
    return np.stack([fx, fy], axis=-1)


@pytest.mark.heavy
def test_periodic_orbit_against_solve_ivp():
    """The code's periodic orbit against scipy's LSODA integration of
    d eps/dt = omega/2 e_z x eps + u, u solving F(eps, u) = W with the force by quadrature
    (``squeeze_by_quadrature``, not the code's routines), the smooth load history,
    integrated from the centre cycle after cycle until it repeats within 1e-6.  The code
    takes the load at 720 angles (linear between them) and two BDF2 steps per angle."""
    n, turns = 720, 2.0
    period = 2 * np.pi * turns
    theta = period * np.arange(n) / n
    guess = [np.array([0.0, -0.1])]

    def rhs(t, e):
        u = squeeze_by_quadrature(e, _load_history(np.array([t]))[0], guess[0])
        guess[0] = u
        return np.array([-0.5 * e[1], 0.5 * e[0]]) + u

    e0 = np.zeros(2)
    prev = None
    for _ in range(12):
        sol = solve_ivp(
            rhs, (0, period), e0, method="LSODA", t_eval=np.append(theta[1:], period), rtol=1e-8, atol=1e-10
        )
        e0 = sol.y[:, -1]
        cyc = np.vstack([e0, sol.y.T[:-1]])  # eps at theta[0] (the cycle's end), theta[1], ...
        if prev is not None and np.max(np.abs(cyc - prev)) < 1e-6:
            break
        prev = cyc
    o = periodic_orbits(_load_history(theta)[None], turns, substeps=2, tol=1e-6)
    assert o.converged.all()
    assert np.max(np.hypot(*(o.eps[0] - cyc).T)) < 1.5e-4  # measured 5.1e-5
    # the peak eccentricity, the quantity the film is judged by
    assert np.max(np.hypot(*o.eps[0].T)) == pytest.approx(np.max(np.hypot(*cyc.T)), abs=5e-5)


_A = np.linspace(-np.pi, np.pi, 4001)[:-1]
_N = np.stack([np.cos(_A), np.sin(_A)])


def squeeze_by_quadrature(eps, w, u):
    """The squeeze velocity u with F(u) = w, F the half-Sommerfeld force by the periodic
    trapezoidal rule on 4000 angles (the kink at the cavitation boundary makes it second
    order), by Newton's method with dF/du = int_{u.n > 0} n n^T / (1 - eps.n)^3 by the same rule."""
    g = 1.0 / (1.0 - eps @ _N) ** 3 * (2 * np.pi / _A.size)
    for _ in range(50):
        on = (u @ _N) > 0
        Nk = _N[:, on] * g[on]
        K = Nk @ _N[:, on].T
        step = np.linalg.solve(K, w - K @ u)
        u = u + step
        if np.linalg.norm(step) <= 1e-13 * (1 + np.linalg.norm(u)):
            return u
    raise AssertionError("the quadrature squeeze velocity did not converge")


@pytest.mark.parametrize("eps", [0.3, 0.7, 0.9])
def test_peak_pressure_steady(eps):
    """Steady load: the peak of Ocvirk's pressure at the bearing's middle,
    p = 3 mu omega (B^2/4) eps sin(t) / (c^2 (1 + eps cos t)^3) (t from the thickest film),
    found by dense sampling, against the code's peak at the steady squeeze velocity."""
    b = JournalBearing(diameter=0.05, width=0.02, clearance=25e-6, viscosity=0.01)
    omega = 300.0
    t = np.linspace(0, np.pi, 200001)
    p_ref = np.max(
        3 * b.viscosity * omega * b.width**2 / 4 * eps * np.sin(t) / (b.clearance**2 * (1 + eps * np.cos(t)) ** 3)
    )
    e = np.array([0.0, -eps])
    u = np.array([0.5 * e[1], -0.5 * e[0]])  # u = d eps/dt - omega_bar e_z x eps per radian, d eps/dt = 0
    p = b.pressure_scale() * omega * peak_pressure_factor(e, u)
    assert p == pytest.approx(p_ref, rel=1e-8)


def test_groove_and_k0_by_hand():
    b = JournalBearing(diameter=0.06, width=0.024, clearance=30e-6, viscosity=0.008)
    assert b.k0 == pytest.approx(0.008 * 0.03 * 0.024**3 / 30e-6**2)
    g = JournalBearing(diameter=0.06, width=0.024, clearance=30e-6, viscosity=0.008, groove="full", groove_width=0.004)
    assert g.land_width == pytest.approx(0.010)
    assert g.k0 == pytest.approx(2 * 0.008 * 0.03 * 0.010**3 / 30e-6**2)
    assert g.pressure_scale() == pytest.approx(1.5 * 0.008 * 0.010**2 / 30e-6**2)


def test_walther_through_its_points_and_between():
    """ASTM D341 (Walther) through nu(40 C) = 68 cSt and nu(100 C) = 8.7 cSt: both points
    back, and at 80 C the value of the log-log line computed here by hand."""
    rho = 860.0
    assert walther_viscosity(68e-6, 8.7e-6, rho, 313.15) == pytest.approx(rho * 68e-6, rel=1e-12)
    assert walther_viscosity(68e-6, 8.7e-6, rho, 373.15) == pytest.approx(rho * 8.7e-6, rel=1e-12)
    w40, w100 = math.log10(math.log10(68.7)), math.log10(math.log10(9.4))
    x40, x100, x80 = math.log10(313.15), math.log10(373.15), math.log10(353.15)
    w80 = w40 + (w100 - w40) * (x80 - x40) / (x100 - x40)
    nu80 = 10 ** (10**w80) - 0.7
    assert walther_viscosity(68e-6, 8.7e-6, rho, 353.15) == pytest.approx(rho * nu80 * 1e-6, rel=1e-12)


def reynolds_fd_load(eps, l_over_d, nt=240, nz=40):
    """The steady load of a finite bearing by finite differences of Reynolds' equation,
    independent of the short-bearing closed form: h = 1 + eps cos(theta),
    d/dth (h^3 dp/dth) + d/dzeta (h^3 dp/dzeta) = 6 dh/dth on zeta = z/R in (-L/D, L/D),
    p = 0 at the edges, periodic in theta, the half-Sommerfeld condition by dropping the
    negative pressures; the load over mu omega R^4 / c^2."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    th = np.arange(nt) * 2 * np.pi / nt
    dth = th[1]
    z = np.linspace(-l_over_d, l_over_d, nz + 2)[1:-1]
    dz = z[1] - z[0]
    i, j = np.meshgrid(np.arange(nt), np.arange(nz), indexing="ij")
    k = (i * nz + j).ravel()
    hp = ((1 + eps * np.cos(th + dth / 2)) ** 3)[i].ravel()
    hm = ((1 + eps * np.cos(th - dth / 2)) ** 3)[i].ravel()
    hc = ((1 + eps * np.cos(th)) ** 3)[i].ravel()
    ii, jj = i.ravel(), j.ravel()
    rows = [k, k, k]
    cols = [((ii + 1) % nt) * nz + jj, ((ii - 1) % nt) * nz + jj, k]
    vals = [hp / dth**2, hm / dth**2, -(hp + hm) / dth**2 - 2 * hc / dz**2]
    for dj in (1, -1):
        ok = (jj + dj >= 0) & (jj + dj < nz)
        rows.append(k[ok])
        cols.append((ii * nz + jj + dj)[ok])
        vals.append((hc / dz**2)[ok])
    A = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nt * nz,) * 2)
    p = np.maximum(spsolve(A.tocsc(), (-6 * eps * np.sin(th))[i].ravel()), 0.0).reshape(nt, nz)
    return math.hypot((p * np.cos(th)[:, None]).sum(), (p * np.sin(th)[:, None]).sum()) * dth * dz


@pytest.mark.parametrize("eps", [0.3, 0.6])
def test_short_bearing_is_the_limit_of_the_finite_bearing(eps):
    """The finite bearing's load (finite differences of Reynolds' equation) tends to
    Ocvirk's as the bearing narrows; at land width / diameter 1/4 the short bearing
    carries more (the finite-length factor corrects it: tests/fe/test_fe_oil_film_finite.py)."""

    def short(ld):  # Ocvirk's load over mu omega R^4 / c^2, L = 2 (L/D) R
        return ocvirk_load(eps) * (2 * ld) ** 3

    assert short(0.1) / reynolds_fd_load(eps, 0.1) == pytest.approx(1.0, abs=0.025)
    at_limit = short(0.25) / reynolds_fd_load(eps, 0.25)
    assert 1.0 < at_limit < 1.15


def _film_layout(sense: int, spec):
    from fe_crank.geometry.shaft import MainBearing, ShaftLayout
    from fe_crank.geometry.spec import BearingLaw

    law = BearingLaw(film=spec)
    return ShaftLayout(
        geometry=None,
        throws=(),
        journals=(),
        bearings=(MainBearing("1", 0, 0.0, 0.02, law), MainBearing("2", 1, 0.1, 0.02, law, thrust=True)),
        stub=0.01,
        pitch=0.1,
        sense=sense,
        nose=None,
        flange=None,
        power_takeoff="rear",
        geometry_file="<test>",
        engine_file="<test>",
    )


@pytest.mark.parametrize("sense", [1, -1])
def test_film_sweep_in_si_units_and_the_shafts_sense(sense):
    """``assess.oil_film.film_sweep`` on two bearings under constant loads, in SI: h_min is
    c (1 - eps) with eps from Ocvirk's relation over the finite-length factor R_fit of the
    bearing's B / D (``fe.oil_film.finite_factor``, checked against Reynolds' equation in
    tests/fe/test_fe_oil_film_finite.py) for W = (mu omega R B^3 / c^2) f(eps) / R_fit, the
    journal sits off the load line in the shaft's sense of rotation (sense +1 turns from +y
    towards +x), the peak pressure is Ocvirk's over R_fit, and a stated slope gives its misalignment
    slope B / 2 and the edge film c - |c eps| - slope B/2 when the slope lies along eps."""
    from fe_crank.assess.loads import FIRING
    from fe_crank.assess.oil_film import film_sweep
    from fe_crank.assess.shaft import BearingState
    from fe_crank.fe.shaft.cycle import BearingLoads
    from fe_crank.fe.shaft.whole_shaft import BearingResult
    from fe_crank.geometry.oil import FilmSpec

    mu, c, d, B, omega, eps = 0.007, 25e-6, 0.056, 0.02, 3000 * math.pi / 30, 0.7
    spec = FilmSpec(clearance=c, viscosity=mu, diameter=d)
    r_fit = float(finite_factor(np.array(eps), np.array(B / d))[0])
    W = mu * (d / 2) * B**3 / c**2 * omega * ocvirk_load(eps) / r_fit
    n = 180
    deg = np.arange(n) * 720.0 / n
    load = np.tile([0.0, -W], (n, 1))
    slope = np.tile([0.0, -2e-4], (n, 1))  # along the load

    def loads(name, f):
        return BearingLoads(name, 0.0, B, d, f, W, W, 0.0, W / (d * B), W / (d * B), slope=slope)

    st = BearingState(omega, FIRING, tuple(BearingResult(loads(k, load), loads(k, 0.5 * load)) for k in "12"))
    (out,) = film_sweep(_film_layout(sense, spec), (st,), deg)
    f = out.bearings[0].with_counterweights
    assert f.converged
    assert f.max_eccentricity == pytest.approx(eps, abs=1e-6)
    assert f.min_film_m == pytest.approx(c * (1 - eps), rel=1e-5)
    e = f.eps[-1]
    assert np.sign(e[0]) == -sense  # off the load line (-y) in the sense of rotation
    t = np.linspace(0, np.pi, 200001)
    p_ref = np.max(3 * mu * omega * B**2 / 4 * eps * np.sin(t) / (c**2 * (1 + eps * np.cos(t)) ** 3))
    assert f.peak_pressure_pa == pytest.approx(p_ref / r_fit, rel=1e-6)
    assert f.max_slope == pytest.approx(2e-4)
    assert f.edge_misalignment_m == pytest.approx(2e-4 * B / 2)
    # the slope along -y, eps at the attitude angle: the edge reaches |c eps + s B/2| by hand
    reach = np.hypot(c * e[0], c * e[1] - 2e-4 * B / 2)
    assert f.min_edge_film_m == pytest.approx(c - reach, rel=1e-6)
    # half the load: a thicker film
    assert out.bearings[0].without_counterweights.min_film_m > f.min_film_m


def test_mobility_inverts_the_film_force():
    """Booker's mobility: the squeeze velocity per unit load gives back that load through
    the half-Sommerfeld force by quadrature (``quad_force``), anywhere in the clearance."""
    rng = np.random.default_rng(7)
    e = rng.uniform(-1, 1, (6, 2))
    e *= (rng.uniform(0, 0.97, 6) / np.hypot(*e.T))[:, None]
    d = rng.normal(size=(6, 2))
    m = mobility(e, d)
    for ek, mk, dk in zip(e, m, d):
        assert np.allclose(quad_force(ek, mk), dk / np.linalg.norm(dk), atol=1e-8)
