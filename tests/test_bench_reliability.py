"""``clutchopt bench``'s reliability section in its quick form: the tool's Monte Carlo and OpenTURNS' on the same
limit states (the wedge centrifuge's active constraints at its worst-case and nominal designs) agree within their
intervals; OpenTURNS' design-point methods see the worst-case design's torque failure that 10^4 samples cannot.

Hand figures: at the nominal design each active constraint sits at its limit at the nominal values, and the
margins are monotone in the scatter, so P(fail) is near 1/2 (the median of a symmetric scatter); at the worst-case
design the torque fails only beyond the friction range's low end, the inertia's +3 sd and the load's high end at
once: about 2e-6 (issue 28), below what 10^4 samples resolve (their 95 % bound for no failure, 3.7e-4)."""

import pytest

from clutchopt.bench import BenchConfig, COLUMN_UNITS
from clutchopt.bench import reliability
from clutchopt.bench.reliability import OPENTURNS, TOOL, reliability_rows

pytest.importorskip("openturns")


@pytest.fixture(scope="module")
def rows():
    return reliability_rows(BenchConfig.quick())


def by(rows, design, constraint, estimator):
    return next(r for r in rows if (r["design"], r["constraint"], r["estimator"]) == (design, constraint, estimator))


def test_every_estimator_on_every_limit_state(rows):
    assert {(r["design"], r["constraint"]) for r in rows} == {(d, c) for d in ("worst case", "nominal")
                                                              for c in ("torque", "finger_bending")}
    assert {r["estimator"] for r in rows} == {e.name for e in TOOL + OPENTURNS}
    assert all(set(r) - {"case", "design", "constraint", "estimator", "note"} <= set(COLUMN_UNITS) for r in rows)
    assert all(r["time_s"] > 0 for r in rows)


@pytest.mark.parametrize("design", ["worst case", "nominal"])
@pytest.mark.parametrize("constraint", ["torque", "finger_bending"])
def test_monte_carlo_agrees_with_openturns(rows, design, constraint):
    tool = by(rows, design, constraint, "clutchopt monte carlo")
    ot = by(rows, design, constraint, "openturns monte carlo")
    assert tool["interval_low"] <= tool["probability"] <= tool["interval_high"]
    assert ot["interval_low"] <= ot["probability"] <= ot["interval_high"]
    assert max(tool["interval_low"], ot["interval_low"]) <= min(tool["interval_high"], ot["interval_high"])
    if design == "nominal":
        assert tool["probability"] == pytest.approx(0.5, abs=0.02)


def test_design_point_methods_see_the_small_probability(rows):
    assert by(rows, "worst case", "torque", "clutchopt monte carlo")["interval_high"] == pytest.approx(3.7e-4, rel=0.01)
    for estimator in ("openturns form", "openturns sorm (breitung)", "openturns importance sampling"):
        assert 5e-7 < by(rows, "worst case", "torque", estimator)["probability"] < 2e-5, estimator


def test_without_openturns_the_section_says_so(monkeypatch):
    monkeypatch.setattr(reliability, "openturns_available", lambda: False)
    rows = reliability_rows(BenchConfig(repeats=1))
    assert {r["estimator"] for r in rows} == {e.name for e in TOOL} | {"openturns"}
    assert "openturns not installed" in rows[-1]["note"]


def test_the_tools_design_point_estimators_agree_with_openturns(rows):
    """The worst-case torque (about 2e-6): both importance samplings' intervals overlap; FORM's beta is one design
    point's, so the two FORMs agree closely (both 3-4 x above the truth: the limit state curves); SORM near IS."""
    tool, ot = (by(rows, "worst case", "torque", f"{who} importance sampling") for who in ("clutchopt", "openturns"))
    assert max(tool["interval_low"], ot["interval_low"]) <= min(tool["interval_high"], ot["interval_high"])
    assert tool["probability"] == pytest.approx(2e-6, rel=0.1)
    form = [by(rows, "worst case", "torque", f"{who} form")["probability"] for who in ("clutchopt", "openturns")]
    assert form[0] == pytest.approx(form[1], rel=0.02) and form[0] > 3 * tool["probability"]
    assert by(rows, "worst case", "torque", "clutchopt sorm (breitung)")["probability"] == pytest.approx(
        tool["probability"], rel=0.1)
