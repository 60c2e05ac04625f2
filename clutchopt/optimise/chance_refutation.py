"""Which estimator decides a chance design's failure probability where its Monte Carlo interval lies above 1 - P
(``clutchopt.optimise.robust.verdict``; docs/robust.md, "Verified").

A chance design puts each active constraint at its target, P(fail) = 1 - P (its performance point, beta corrected
until importance sampling meets the target), so the 95 % Clopper-Pearson interval of a Monte Carlo lies wholly above
1 - P with probability about 2.5 % per constraint however true the design: an unlucky draw, not a miss (with 2000
samples at P(fail) = 0.01 the expected 20 failures reach 32 about once in 50). Where it does, the more accurate
estimate of the same probability decides: importance sampling at the constraint's design point (50,000 samples, a
start-up limit's of its simulated starts) or an exact one (a constraint independent of the scatter), provided the
two agree: the Monte Carlo's interval at 1 - DISAGREEMENT reaches the accurate estimate's interval. Where even that
wider interval lies above it, the Monte Carlo saw failures the accurate estimator did not (a failure region away
from the design point, which sampling centred there misses): the Monte Carlo decides and the design is refused. The
accurate estimate refuses on its own where its interval lies above 1 - P (``verdict``). FORM and SORM give no
interval and do not overrule a Monte Carlo.
"""

from __future__ import annotations

from dataclasses import dataclass

from clutchopt.optimise.reliability import Estimate
from clutchopt.optimise.robust_models import clopper_pearson

DISAGREEMENT = 1e-4  # two-sided: a true design is refused where the two agree with probability below 5e-5
MORE_SAMPLES = 10  # an importance sampling overrules a Monte Carlo only with at least this many times its samples
# (a start-up limit's, drawn from the Monte Carlo's own simulated starts, is no more accurate than it and does not)
VERIFIED_FACTOR = 2.0  # a chance design's failure probability is verified when its interval lies below this x 1 - P;
# a Monte Carlo whose 95 % interval lies above it refuses whatever overrules it (no more passes than importance
# sampling alone would let pass: ``robust.verdict``)
MONTE_CARLO = "Monte Carlo"


def decides(estimate: Estimate | None) -> bool:
    """An estimate accurate enough to overrule a Monte Carlo: sampled with an interval, or exact."""
    return estimate is not None and (estimate.estimator == "importance sampling"
                                     or estimate.estimator.startswith("exact"))


@dataclass(frozen=True)
class MonteCarloAbove:
    """One constraint (or start-up limit) whose Monte Carlo interval lies wholly above 1 - P, and what decided it."""

    name: str
    monte_carlo: list[float]  # [p, low, high], CONFIDENCE Clopper-Pearson
    samples: int  # of the Monte Carlo
    accurate: Estimate | None  # the more accurate estimate, where there is one
    accurate_samples: int  # of the importance sampling (0: exact)
    wide: list[float]  # [p, low, high] of the Monte Carlo at 1 - DISAGREEMENT
    allowed: float  # 1 - P

    @property
    def kept_by_monte_carlo(self) -> str | None:
        """Why the Monte Carlo decides (the accurate estimate cannot overrule it), in words; None where it can."""
        if not decides(self.accurate):
            return "no importance sampling or exact estimate to decide"
        if 0 < self.accurate_samples < MORE_SAMPLES * self.samples:
            return (f"its {self.accurate.estimator} ({self.accurate_samples} samples) is not {MORE_SAMPLES} times "
                    "its samples")
        if self.monte_carlo[1] > VERIFIED_FACTOR * self.allowed:
            return f"its interval lies above {VERIFIED_FACTOR:g} x {self.allowed:.3g}"
        if self.wide[1] > self.accurate.high:
            return "disagree"
        return None

    @property
    def decided_by(self) -> str:
        """The estimator that decided: the accurate one where it may overrule the Monte Carlo
        (:attr:`kept_by_monte_carlo`), else Monte Carlo."""
        return MONTE_CARLO if self.kept_by_monte_carlo else self.accurate.estimator

    @property
    def refused(self) -> bool:
        """The Monte Carlo decided (its interval lies above 1 - P). Where the accurate estimate decided, ``verdict``
        refuses by it, where its own interval lies above 1 - P."""
        return self.decided_by == MONTE_CARLO

    def text(self, allowed: float) -> str:
        p, low, high = self.monte_carlo
        shown = f"{self.name} fails with probability {p:.3g} ({low:.3g} to {high:.3g}) > {allowed:.3g}"
        why = self.kept_by_monte_carlo
        if why is not None and why != "disagree":
            return shown + f" ({why})"
        e = self.accurate
        accurate = (f"{e.estimator} {e.probability:.3g} ({e.low:.3g} to {e.high:.3g}"
                    + (f", {self.accurate_samples} samples at its design point)" if self.accurate_samples else ")"))
        if self.refused:
            return (shown + f"; it saw failures {accurate} did not: its {1 - DISAGREEMENT:.2%} interval "
                            f"{self.wide[1]:.3g} to {self.wide[2]:.3g} lies above it")
        return (f"{self.name}: Monte Carlo {p:.3g} ({low:.3g} to {high:.3g}) above {allowed:.3g}, decided by "
                f"{accurate}, within the Monte Carlo's {1 - DISAGREEMENT:.2%} interval ({self.wide[1]:.3g} to "
                f"{self.wide[2]:.3g})")

    def as_dict(self) -> dict:
        return {"name": self.name, "monte_carlo": self.monte_carlo, "samples": self.samples,
                "decided_by": self.decided_by, "estimate": self.accurate.as_dict() if self.accurate else None,
                "estimate_samples": self.accurate_samples, "monte_carlo_wide": self.wide,
                "wide_confidence": 1 - DISAGREEMENT, "refused": self.refused}


def monte_carlo_above(failure: dict[str, list[float]], samples: int, estimates: dict[str, Estimate],
                      accurate_samples: int, allowed: float) -> list[MonteCarloAbove]:
    """Each entry of ``failure`` (name -> [p, low, high] of ``samples`` Monte Carlo draws) whose interval lies wholly
    above ``allowed``, beside its estimate in ``estimates`` (of ``accurate_samples`` importance samples)."""
    out = []
    for name, (p, low, high) in failure.items():
        if low > allowed:
            estimate = estimates.get(name)
            out.append(MonteCarloAbove(name, [p, low, high], samples, estimate,
                                       accurate_samples if estimate and estimate.estimator == "importance sampling" else 0,
                                       clopper_pearson(round(p * samples), samples, 1 - DISAGREEMENT), allowed))
    return out
