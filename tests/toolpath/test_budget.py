"""The tolerance budgets (camcam.toolpath.budget): frozen, every share documented, and where shares split one
tolerance they add up to at most all of it."""

from __future__ import annotations

import dataclasses

import pytest

from camcam.toolpath.budget import (DEFAULT_BUDGET, DEFAULT_FIVE_AXIS_BUDGET, DEFAULT_GROOVE_BUDGET, FitBudget,
                                    FiveAxisBudget, GrooveBudget)
from camcam.toolpath.quantizer import Quantizer

BUDGETS = (FitBudget, GrooveBudget, FiveAxisBudget)


@pytest.mark.parametrize("cls", BUDGETS)
def test_budget_is_frozen_and_every_share_documented(cls):
    b = cls()
    field = dataclasses.fields(cls)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(b, field, 0.0)
    params = cls.__doc__.split("Parameters")[1]
    for f in dataclasses.fields(cls):
        assert f.name in params, f"{cls.__name__}.{f.name} is not documented"


def test_defaults_are_the_default_objects():
    assert DEFAULT_BUDGET == FitBudget() and DEFAULT_GROOVE_BUDGET == GrooveBudget()
    assert DEFAULT_FIVE_AXIS_BUDGET == FiveAxisBudget()


def test_fit_budget_shares_split_the_contour_tolerance():
    """δ = rounding + 2 sampling margins + the fit: with the fit's least share the two margins leave room for the
    rounding (else no tolerance would hold, floor_mm would be negative or infinite)."""
    b = FitBudget()
    assert 2 * b.sampling_share + b.min_fit_share < 1
    assert b.floor_mm(Quantizer(4)) > 0
    # the march's band leaves the final measurement's margin and its own sampling (half of it): within δ
    assert b.sampling_share + b.sampling_share / 2 <= b.spline_sampling_share <= 1
    # the chain's band keeps more than chain_min_share of the spline band, and its G1 gap is spent inside that
    assert b.chain_min_share + b.chain_gap_share <= 1
    assert 0 < b.polygon_share <= 1 and 0 < b.retry_factor < 1 and 0 < b.spline_retry_factor < 1


def test_groove_budget_shares_split_the_groove_tolerance():
    """The flank plan's error and the flank passes' fit share one tolerance T; a tilting roller's fit share and
    the 3-D measurement's sampling share leave the machine's error the rest (the advice divides by it)."""
    g = GrooveBudget()
    assert g.flank_share + g.flank_fit_share <= 1
    assert g.tilt_fit_share + g.sampling_share < 1
    # with a tool from the smallest one up (e ≤ flank_share·T), the fit keeps T − e ≥ flank_fit_share·T
    t = 0.01
    e = g.flank_tool_mm(t)
    assert g.flank_fit_mm(t, e) + e <= t * (1 + 1e-12)
    assert g.flank_fit_mm(t, 0.9 * t) == g.flank_fit_share * t
    # the advised tolerance holds what was measured plus the fit's share at that tolerance
    advised = g.tilt_tolerance_mm(0.03, t)
    assert advised * (1 - g.tilt_fit_share - g.sampling_share) == pytest.approx(0.03 + g.tilt_fit_share * t)


def test_five_axis_budget_leaves_the_measurement_its_share():
    """The 5-axis fit's share and the 3-D measurement's sampling share split one tolerance."""
    assert FiveAxisBudget().fit_share + GrooveBudget().sampling_share <= 1


def test_pose_step_bound_is_the_sampling_share():
    g = GrooveBudget()
    h = g.pose_step_for(0.001, 8.0)
    assert h * h / (8 * 8.0) <= g.sampling_share * 0.001 * (1 + 1e-12)
    assert g.pose_step_for(1.0, 8.0) == g.pose_step_mm
