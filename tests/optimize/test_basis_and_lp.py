"""The B-spline space's own basis (exact cardinal pieces) and the HiGHS LP calls, against scipy.

scipy is the independent reference here: ``BSpline`` (de Boor's recursion) and
``PPoly.from_spline`` for the basis, ``linprog(method="highs-ds")`` for the LP.
camcam itself calls neither on the ``camcam optimize`` path (their imports cost
more than the solve), so these tests are what ties the two together.
"""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.interpolate import BSpline, PPoly
from scipy.optimize import linprog

from camcam.optimize.evaluation import Problem
from camcam.optimize.exact import exact_optimum
from camcam.optimize.lp import IncrementalLp, solve_lp
from camcam.optimize.space import BSplineSpace, cardinal_pieces

TABLE1_SPEC = Path(__file__).resolve().parents[2] / "samples" / "optimize" / "table1.toml"


@pytest.mark.parametrize("degree", [3, 5, 7, 9])
@pytest.mark.parametrize("segments,symmetric", [(4, True), (7, True), (12, False), (18, False)])
def test_basis_matrix_is_scipys_bspline(degree, segments, symmetric):
    sp = BSplineSpace(degree, segments, symmetric)
    ref = BSpline(sp.knots, np.eye(sp.n_control), degree)
    # every knot (the ends included) and points between them
    T = np.unique(np.r_[np.linspace(0.0, sp.span, 4 * segments + 1), np.random.default_rng(1).uniform(0, sp.span, 40)])
    for nu in range(degree):
        got, want = sp.basis_matrix(T, nu), ref(T, nu=nu)
        # two evaluations of the same polynomials (power form against de Boor's recursion) differ by rounding
        # only: 6.4e-15 of the largest value at worst over these 16 spaces × derivatives, so 1e-13 relative
        assert np.abs(got - want).max() <= 1e-13 * np.abs(want).max()


@pytest.mark.parametrize("degree", [3, 5])
def test_power_coefficients_are_ppoly_from_spline(degree):
    # PPoly.from_spline goes through FITPACK's splev, which takes degrees up to 5 only (degree 9 crashed the
    # process there: the reason camcam builds the coefficients itself)
    sp = BSplineSpace(degree, 7, True)
    n, N = degree, 7
    for j in range(sp.n_control):
        pp = PPoly.from_spline(BSpline(sp.knots, np.eye(sp.n_control)[j], n))
        want = pp.c[::-1, n:n + N].T
        # the exact integers over n! rounded once, against FITPACK's derivatives: relative 1e-13 of the largest
        # coefficient of the piece (h^-n ≈ 5e4 at degree 5, N = 7)
        assert np.abs(sp._Q[:, :, j] - want).max() <= 1e-13 * np.abs(want).max()


def test_cardinal_pieces_are_a_partition_of_unity_with_exact_knot_values():
    for n in range(1, 10):
        C = cardinal_pieces(n)
        # Σ_m M_n(m + s) = 1 for all s: the coefficient sums over the pieces are (1, 0, 0, …) exactly up to
        # rounding of integers / n! (at most 9! = 362880, well inside 2^53)
        assert np.abs(C.sum(axis=0) - np.eye(1, n + 1)[0]).max() <= 1e-12
        # M_n is symmetric about (n + 1)/2: piece m at s equals piece n − m at 1 − s
        s = np.linspace(0, 1, 7)
        vals = np.polynomial.polynomial.polyval(s, C.T)
        assert np.allclose(vals, vals[::-1, ::-1], rtol=0, atol=1e-13)  # values ≤ 1: rounding only


def test_degree_9_space_optimises():
    # Regression: BSplineSpace(9, …) segfaulted in scipy's FITPACK (PPoly.from_spline, degrees ≤ 5 only),
    # killing `camcam optimize` with degree = 9, which the spec accepts (MAX_DEGREE).
    r = exact_optimum(Problem(9, 10, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    # every curve is above the continuous optimum a* = 4.72821 of benchmarks/optimize_tables.py
    # (bang-bang jerk, closed form there); the LP meets the limits literally
    assert r.objective >= 4.72821
    assert r.worst_violation == 0.0


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 100_000), n=st.integers(2, 6), m=st.integers(1, 12))
def test_solve_lp_agrees_with_linprog(seed, n, m):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(m, n))
    b = rng.uniform(0.5, 2.0, m)  # x = 0 is feasible
    c = rng.normal(size=n)
    lo, hi = -rng.uniform(0.5, 3.0, n), rng.uniform(0.5, 3.0, n)  # bounded: an optimum exists
    ref = linprog(c, A_ub=A, b_ub=b, bounds=list(zip(lo, hi)), method="highs-ds")
    got = solve_lp(c, A, b, lo, hi)
    assert ref.status == 0 and got.status == "optimal"
    # the same solver on the same problem: objectives within HiGHS's feasibility tolerances (1e-7) × |c|·|x|
    assert abs(c @ got.x - ref.fun) <= 1e-7 * (1.0 + np.abs(c).sum() * 3.0)
    assert (A @ got.x <= b + 1e-7).all() and (got.x >= lo - 1e-7).all() and (got.x <= hi + 1e-7).all()


def test_rows_added_in_batches_give_the_one_shot_optimum():
    rng = np.random.default_rng(7)
    A, b, c = rng.normal(size=(30, 4)), rng.uniform(0.5, 2.0, 30), rng.normal(size=4)
    lo, hi = np.full(4, -5.0), np.full(4, 5.0)
    lp = IncrementalLp(c, lo, hi)
    for k in range(0, 30, 7):
        lp.add_rows(A[k:k + 7], b[k:k + 7])
        batched = lp.solve()
    one = solve_lp(c, A, b, lo, hi)
    assert batched.status == one.status == "optimal"
    assert abs(c @ batched.x - c @ one.x) <= 1e-9  # one LP, two routes to its optimum: solver tolerance
    with pytest.raises(ValueError, match="4 columns"):
        lp.add_rows(np.ones((1, 3)), np.ones(1))


def test_infeasible_lp_says_so():
    got = solve_lp(np.ones(1), np.array([[1.0], [-1.0]]), np.array([-1.0, -1.0]), np.full(1, -np.inf),
                   np.full(1, np.inf))  # x ≤ −1 and x ≥ 1
    assert got.status == "infeasible"


def test_optimize_exact_imports_no_scipy(tmp_path):
    # `camcam optimize` (exact) is meant to take at most 0.5 s (issue 13); importing scipy.optimize or
    # scipy.interpolate alone takes longer on a 2-core machine, so the command must not import scipy at all
    code = (
        "import sys\n"
        "from camcam.cli import main\n"
        f"rc = main(['optimize', {str(TABLE1_SPEC)!r}, '-o', {str(tmp_path / 'law.json')!r}])\n"
        "print(rc, sorted({m.split('.')[0] for m in sys.modules if m.split('.')[0] in ('scipy', 'matplotlib')}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.splitlines()[-1] == "0 []"
    assert (tmp_path / "law.json").exists()
