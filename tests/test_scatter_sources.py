"""Sources of scatter (issue 28, item 3): lognormal and cut normal distributions, relative bands, the library's
friction range, and correlation ([scatter.correlation]) reaching the Monte Carlo; every refusal through the CLI.

Hand calculations (docs/robust.md, "The section"):
- lognormal of mean m, sd s: sigma^2 = ln(1 + (s/m)^2), mu = ln m - sigma^2/2; its worst-case range the quantiles
  exp(mu -+ 3 sigma). m = 12, s = 0.6: sigma^2 = ln 1.0025 = 2.496880e-3, sigma = 0.04996879, mu = 2.483658,
  exp(mu - 3 sigma) = 10.31658 and exp(mu + 3 sigma) = 13.92331.
- normal (mu, s) cut to [a, b], alpha = (a - mu)/s, beta = (b - mu)/s, Z = Phi(beta) - Phi(alpha):
  mean = mu + s (phi(alpha) - phi(beta)) / Z, variance = s^2 (1 + (alpha phi(alpha) - beta phi(beta))/Z
  - ((phi(alpha) - phi(beta))/Z)^2).
- "+-20 %" around 0.15: 0.12 .. 0.18; "+-25 %" around 20 N m: 15 .. 25 N m.
- Gaussian copula: for two normal quantities the sample correlation of the draws is rho (standard error
  (1 - rho^2)/sqrt(n): 0.0036 for rho = 0.5, n = 40,000).
"""

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from clutchopt.cases import load_case, parse_case
from clutchopt.cli import EXIT_BAD_INPUT, main
from clutchopt.scatter import Scatter, draw

CASES = Path(__file__).resolve().parents[1] / "cases"
CENTRIFUGE = (CASES / "wedge_centrifuge.toml").read_text()
BARE = CENTRIFUGE[:CENTRIFUGE.index("[scatter]")]
COUNT = 200_000


def scattered(table: str, base: str = BARE) -> str:
    return f"{base}\n[scatter]\n{table}\n"


def read(text: str, tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(text)
    return load_case(path)


LOGNORMAL = Scatter("inertia", "lognormal", math.nan, math.nan, 2.0, 1.0)  # skewed: sd half the mean
TRUNCATED = Scatter("friction_coefficient", "truncated", 0.12, 0.17, 0.15, 0.02)
KINDS = [Scatter("inertia", "normal", 10.2, 13.8, 12.0, 0.6), LOGNORMAL, TRUNCATED,
         Scatter("friction_coefficient", "range", 0.12, 0.18, 0.15, 0.06 / math.sqrt(12))]


def truncated_moments(mu, s, a, b):
    alpha, beta = (a - mu) / s, (b - mu) / s
    z = stats.norm.cdf(beta) - stats.norm.cdf(alpha)
    pa, pb = stats.norm.pdf(alpha), stats.norm.pdf(beta)
    mean = mu + s * (pa - pb) / z
    variance = s ** 2 * (1 + (alpha * pa - beta * pb) / z - ((pa - pb) / z) ** 2)
    return mean, math.sqrt(variance)


def test_lognormal_from_its_mean_and_sd():
    sigma = math.sqrt(math.log(1 + (1.0 / 2.0) ** 2))
    mu = math.log(2.0) - sigma ** 2 / 2
    assert LOGNORMAL.log_parameters() == pytest.approx((mu, sigma), rel=1e-14)
    x = draw([LOGNORMAL], np.random.default_rng(1), COUNT)[LOGNORMAL.name]
    assert x.mean() == pytest.approx(2.0, abs=4 * 1.0 / math.sqrt(COUNT))  # 4 standard errors
    assert x.std() == pytest.approx(1.0, rel=0.02)
    assert x.min() > 0


def test_cut_normal_moments():
    mean, sd = truncated_moments(0.15, 0.02, 0.12, 0.17)
    law = stats.truncnorm(-1.5, 1.0, 0.15, 0.02)  # alpha = (0.12 - 0.15)/0.02, beta = (0.17 - 0.15)/0.02
    assert (mean, sd) == pytest.approx((law.mean(), law.std()), rel=1e-10)
    assert mean < 0.15  # cut closer above: the mean moves down
    x = draw([TRUNCATED], np.random.default_rng(2), COUNT)[TRUNCATED.name]
    assert x.min() >= 0.12 and x.max() <= 0.17
    assert x.mean() == pytest.approx(mean, abs=4 * sd / math.sqrt(COUNT))
    assert x.std() == pytest.approx(sd, rel=0.01)


@pytest.mark.parametrize("scatter", KINDS, ids=lambda s: s.kind)
def test_maps_to_and_from_standard_normal(scatter):
    u = np.linspace(-5, 5, 41)
    x = scatter.from_standard(u)
    assert np.all(np.diff(x) > 0)
    assert scatter.to_standard(x) == pytest.approx(u, abs=1e-9)
    law = {"normal": stats.norm(12.0, 0.6),
           "lognormal": stats.lognorm(LOGNORMAL.log_parameters()[1], scale=math.exp(LOGNORMAL.log_parameters()[0])),
           "truncated": stats.truncnorm(-1.5, 1.0, 0.15, 0.02), "range": stats.uniform(0.12, 0.06)}[scatter.kind]
    for p in (1e-6, 0.00135, 0.1, 0.5, 0.9, 0.99865, 1 - 1e-6):
        assert float(scatter.from_standard(stats.norm.ppf(p))) == pytest.approx(float(law.ppf(p)), rel=1e-9)


def test_kinds_read_from_a_case_with_their_worst_case_ranges(tmp_path):
    case = read(scattered('inertia = { lognormal = ["12 kg*m^2", "0.6 kg*m^2"] }\n'
                          'friction_coefficient = { normal = [0.15, 0.02], within = [0.12, 0.17] }\n'
                          'resisting_torque = "+-25 %"'), tmp_path)
    inertia, friction, load = case.scatter
    assert (inertia.kind, inertia.mean, inertia.sd) == ("lognormal", 12.0, 0.6)
    assert (inertia.low, inertia.high) == pytest.approx((10.31658, 13.92331), abs=1e-5)  # exp(mu -+ 3 sigma)
    assert (friction.kind, friction.low, friction.high, friction.mean, friction.sd) == ("truncated", 0.12, 0.17,
                                                                                       0.15, 0.02)
    assert (load.kind, load.low, load.high) == ("range", 15.0, 25.0)
    assert "within 0.12 to 0.17" in friction.describe(lambda v: f"{v:g}")


def test_relative_band_is_the_range_it_spells(tmp_path):
    for band in ('"+-20 %"', '"±20 %"', '"+/-20%"'):
        friction = read(scattered(f"friction_coefficient = {band}"), tmp_path).scatter[0]
        assert (friction.kind, friction.low, friction.high) == ("range", pytest.approx(0.12), pytest.approx(0.18))


def test_library_range(tmp_path):
    named = BARE.replace("friction_coefficient = 0.15\n", "") + '\n[library]\nfriction_pair = "steel_steel_dry"\n'
    case = read(scattered('friction_coefficient = "library"', named), tmp_path)
    assert case.values["friction_coefficient"] == 0.18  # Juvinall & Marshek table 18.1: f 0.15-0.25
    assert (case.scatter[0].low, case.scatter[0].high) == (0.15, 0.25)
    own = read(scattered('friction_coefficient = "library"', named.replace("[material]", "[material]\n"
                                                                           "friction_coefficient = 0.2")), tmp_path)
    assert (own.values["friction_coefficient"], own.scatter[0].low, own.scatter[0].high) == (0.2, 0.15, 0.25)


CORRELATED = scattered('inertia = { normal = ["12 kg*m^2", "0.6 kg*m^2"] }\n'
                       'allowable_pressure = { normal = ["1.5 MPa", "0.1 MPa"] }\n'
                       'friction_coefficient = [0.12, 0.18]\n'
                       '[scatter.correlation]\ninertia.allowable_pressure = 0.5\nfriction_coefficient.inertia = -0.3')


def test_correlation_matrix_and_draws(tmp_path):
    case = read(CORRELATED, tmp_path)
    assert case.correlation == ((1.0, 0.5, -0.3), (0.5, 1.0, 0.0), (-0.3, 0.0, 1.0))
    drawn = draw(case.scatter, np.random.default_rng(3), 40_000, case.correlation)
    assert np.corrcoef(drawn["inertia"], drawn["allowable_pressure"])[0, 1] == pytest.approx(0.5, abs=0.015)
    friction = case.scatter[2]
    scores = friction.to_standard(drawn["friction_coefficient"])
    assert np.corrcoef(drawn["inertia"], scores)[0, 1] == pytest.approx(-0.3, abs=0.02)  # of the normal scores
    independent = draw(case.scatter, np.random.default_rng(3), 40_000)
    assert abs(np.corrcoef(independent["inertia"], independent["allowable_pressure"])[0, 1]) < 0.02


def test_correlation_reaches_the_monte_carlo(tmp_path, monkeypatch, capsys):
    """A robust solve samples its verification through draw() with the case's correlation."""
    import clutchopt.optimise.robust_models as models

    seen = []

    def spy(scatters, rng, count, correlation=None):
        seen.append((correlation, draw(scatters, rng, count, correlation)))
        return seen[-1][1]

    monkeypatch.setattr(models, "draw", spy)
    path = tmp_path / "case.toml"
    path.write_text(CORRELATED)
    assert main(["solve", str(path), "--robust", "worst-case", "--samples", "2000", "--no-store"]) == 0
    assert ("correlated (of the normal scores; the corners do not change): inertia with allowable_pressure +0.5; "
            "inertia with friction_coefficient -0.3") in capsys.readouterr().out
    assert seen and all(correlation == read(CORRELATED, tmp_path).correlation for correlation, _ in seen)
    drawn = seen[0][1]
    assert np.corrcoef(drawn["inertia"], drawn["allowable_pressure"])[0, 1] == pytest.approx(0.5, abs=0.06)


BAD = [
    ("correlation-unknown", CORRELATED + "speedd.inertia = 0.2", "scatter.correlation.speedd: not a scattered"),
    ("correlation-unscattered", CORRELATED + "speed.inertia = 0.2", "scatter.correlation.speed: not a scattered"),
    ("correlation-unscattered-second", CORRELATED + "allowable_pressure.speed = 0.2",
     "scatter.correlation.allowable_pressure.speed: not a scattered"),
    ("correlation-one", CORRELATED + "allowable_pressure.friction_coefficient = 1.0",
     "scatter.correlation.allowable_pressure.friction_coefficient: must be a number above -1 and below 1"),
    ("correlation-text", CORRELATED + 'allowable_pressure.friction_coefficient = "high"',
     "scatter.correlation.allowable_pressure.friction_coefficient: must be a number"),
    ("correlation-itself", CORRELATED + "allowable_pressure.allowable_pressure = 0.5",
     "scatter.correlation.allowable_pressure.allowable_pressure: a quantity with itself"),
    ("correlation-twice", CORRELATED + "allowable_pressure.inertia = 0.4",
     "scatter.correlation.allowable_pressure.inertia: given twice: also as scatter.correlation.inertia."
     "allowable_pressure"),
    ("correlation-not-positive-definite", CORRELATED.replace("= -0.3", "= 0.9").replace("= 0.5", "= 0.9")
     + "allowable_pressure.friction_coefficient = -0.9",
     "scatter.correlation: the correlations of inertia, allowable_pressure, friction_coefficient are not positive "
     "definite"),
    ("correlation-not-a-table", scattered("friction_coefficient = [0.12, 0.18]\ncorrelation = 0.5"),
     "scatter.correlation: must be a table"),
    ("band-low-end", scattered('radius_ratio = "+-30 %"'),
     "scatter.radius_ratio: the band's low end 0.875 (1.25 - 30 %) leaves the quantity's valid range: must be > 1"),
    ("band-high-end", scattered('finger_fit_ratio = "+-150 %"'), "above 0 % and below 100 %"),
    ("band-high-end-of-the-range", scattered(
        'friction_coefficient = "+-20 %"', BARE.replace("friction_coefficient = 0.15", "friction_coefficient = 0.9")),
     "scatter.friction_coefficient: the band's high end 1.08 (0.9 + 20 %) leaves the quantity's valid range: "
     "must be <= 1"),
    ("band-spelling", scattered('friction_coefficient = "20 %"'), "scatter.friction_coefficient: must be [low, high]"),
    ("library-without-a-pair", scattered('friction_coefficient = "library"'),
     'scatter.friction_coefficient: "library" takes the range of the friction or thread pair'),
    ("library-for-inertia", scattered('inertia = "library"', BARE + '[library]\nfriction_pair = "steel_steel_dry"\n'),
     'scatter.inertia: "library" takes the range'),
    ("library-case-value-outside", scattered('friction_coefficient = "library"',
                                             BARE + '[library]\nfriction_pair = "organic_dry"\n'),
     "scatter.friction_coefficient: the case's value 0.15 lies outside 0.25 .. 0.45"),
    ("lognormal-mean", scattered('inertia = { lognormal = ["10 kg*m^2", "0.6 kg*m^2"] }'),
     "scatter.inertia.lognormal: the mean 10 kg*m^2 is not the case's value 12 kg*m^2"),
    ("lognormal-sd", scattered('inertia = { lognormal = ["12 kg*m^2", "0 kg*m^2"] }'),
     "scatter.inertia.lognormal: the standard deviation must be positive"),
    ("cut-normal-outside", scattered("friction_coefficient = { normal = [0.15, 0.02], within = [0.16, 0.2] }"),
     "scatter.friction_coefficient.within: the case's value 0.15 lies outside 0.16 .. 0.2"),
    ("cut-normal-mean", scattered("friction_coefficient = { normal = [0.14, 0.02], within = [0.1, 0.2] }"),
     "scatter.friction_coefficient.normal: the mean 0.14 is not the case's value 0.15"),
]


@pytest.mark.parametrize("text, expected", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_refused_by_name(tmp_path, capsys, text, expected):
    path = tmp_path / "case.toml"
    path.write_text(text)
    assert main(["solve", str(path), "--robust", "worst-case"]) == EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    assert out == "" and all(line.startswith("error: ") for line in err.splitlines()) and "Traceback" not in err
    assert expected in err, err


def test_correlation_leaves_the_corners(tmp_path):
    """Corners are of the ranges: a correlation changes sampling only (docs/robust.md)."""
    with_correlation = read(CORRELATED, tmp_path)
    without = parse_case(tomllib.loads(CORRELATED.split("[scatter.correlation]")[0]))
    assert with_correlation.scatter == without.scatter and without.correlation is None


def test_a_cut_normal_is_designed_at_its_cut(tmp_path):
    """Worst case: each constraint at its corner of the ranges, and a cut normal's range is its cut, so f normal
    (0.15, 0.02) within [0.12, 0.18] gives the design of f over [0.12, 0.18] (the case's own: 1.43600 kg, README;
    by hand, tests/test_reliability.py's closed forms: m = (13.8 kg m^2 w / 30 s + 25 N m) / (0.12 C) = 0.228601 kg,
    the fingers for f = 0.18)."""
    from clutchopt.optimise.robust import WORST_CASE, solve_robust

    cut = read(scattered('friction_coefficient = { normal = [0.15, 0.02], within = [0.12, 0.18] }\n'
                         'inertia = { normal = ["12 kg*m^2", "0.6 kg*m^2"] }\n'
                         'resisting_torque = ["15 N*m", "25 N*m"]'), tmp_path)
    assert solve_robust(cut, WORST_CASE).solution.objective == pytest.approx(1.43600, rel=1e-5)


def test_correlation_in_the_json_and_the_run_store(tmp_path, capsys):
    """`solve --robust --json` and the stored run keep each quantity's scatter and whom it is correlated with."""
    import json

    from clutchopt.store import RunStore

    path = tmp_path / "case.toml"
    path.write_text(CORRELATED)
    store = tmp_path / "runs.sqlite"
    assert main(["solve", str(path), "--robust", "worst-case", "--samples", "2000", "--json",
                 "--store", str(store)]) == 0
    data = json.loads(capsys.readouterr().out)
    scatter = data["robust"]["scatter"]
    assert data["robust"]["units"]["scatter"]["inertia"] == {"low": "kg*m^2", "high": "kg*m^2", "mean": "kg*m^2",
                                                           "sd": "kg*m^2", "correlation": ""}
    assert scatter["inertia"]["correlation"] == {"allowable_pressure": 0.5, "friction_coefficient": -0.3}
    assert scatter["friction_coefficient"]["correlation"] == {"inertia": -0.3}
    assert scatter["allowable_pressure"]["correlation"] == {"inertia": 0.5}
    assert scatter["inertia"]["mean"] == 12.0 and scatter["inertia"]["sd"] == pytest.approx(0.6)
    with RunStore(store) as runs:
        record = runs.run(runs.runs()[-1]["id"])
    assert record["inputs"]["scatter"]["inertia"]["correlation"] == {"allowable_pressure": 0.5,
                                                                     "friction_coefficient": -0.3}
    assert record["inputs"]["scatter"]["friction_coefficient"]["correlation"] == {"inertia": -0.3}
