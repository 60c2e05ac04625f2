"""Every design command takes every case (issue 23, point 6): generated, not hand-listed. Each command x coupling x
aspect combination (tests/composition.py) x mode either exits 0 with verified results or exits 2 with a named
reason, and the commands agree with each other: a sweep's point at the case's own values is `solve`'s design,
pareto's lightest end is `solve`'s, the report's headline objective is `solve`'s (with the same flags)."""

import json
import re

import pytest

from clutchopt.cases import load_case
from clutchopt.units import from_si
from tests.composition import ASPECTS, SWEPT, case_data, combinations, run, toml_text

SAMPLES = "100"  # the Monte Carlo check's least: what is tested here is that the aspects compose
_SOLVED: dict[tuple, tuple[int, dict | str]] = {}  # solve of each case and flags, once per worker


def _flags(aspects) -> list[str]:
    robust = {"worst-case": "worst-case", "chance": "chance=0.99"}
    method = next((robust[a] for a in aspects if a in robust), None)
    return ["--robust", method, "--samples", SAMPLES, "--starts", "10"] if method else []


def _case(tmp_path, coupling, aspects):
    path = tmp_path / f"{coupling}_{'_'.join(aspects) or 'plain'}.toml"
    path.write_text(toml_text(case_data(coupling, aspects)), encoding="utf-8")
    return path


def _solved(tmp_path, coupling, aspects, mode):
    key = (coupling, aspects, mode)
    if key not in _SOLVED:
        code, out, err = run("solve", _case(tmp_path, coupling, aspects), "--mode", mode, "--json", "--no-store",
                             *_flags(aspects))
        _SOLVED[key] = (code, json.loads(out) if code == 0 else err)
    return _SOLVED[key]


def _verified(record: dict) -> None:
    """An optimal design passed its float64 check; any other verdict says why."""
    if record["status"] == "optimal":
        assert all(c["feasible"] for c in record["constraints"]), record["constraints"]
    else:
        assert record["diagnosis"], record["status"]


def _named(err: str) -> None:
    lines = err.strip().splitlines()
    assert lines and all(re.match(r"error: [^:]+: \S", line) for line in lines), err


def _design_equal(design: dict, expected: dict) -> None:
    for name, value in expected.items():
        assert design[name] == pytest.approx(value, rel=1e-8, abs=1e-12), name


@pytest.mark.parametrize("command, coupling, aspects, mode", combinations(),
                         ids=lambda v: "+".join(v) or "plain" if isinstance(v, tuple) else v)
def test_every_command_takes_every_case(command, coupling, aspects, mode, tmp_path):
    path = _case(tmp_path, coupling, aspects)
    flags = _flags(aspects)
    solved_code, solved = _solved(tmp_path, coupling, aspects, mode)
    if command == "solve":
        if solved_code == 2:
            return _named(solved)
        assert solved_code == 0
        for record in [solved, *(solved.get("choices") or [])]:
            _verified(record)
        return
    if command == "compare":
        code, out, err = run("compare", path, "--json", *flags)
        if code == 2:
            return _named(err)
        assert code == 0, err
        for solve in json.loads(out)["solves"].values():
            assert solve["status"] == "optimal" or solve["diagnosis"], solve
        return
    if command == "sweep":
        case = load_case(path)
        quantity = next(q for q in case.quantities if q.name == SWEPT[coupling])
        own = from_si(case.values[quantity.name], quantity.unit)
        code, out, err = run("sweep", path, "--mode", mode, "--vary", f"{quantity.name}={own!r}", "--json",
                             "--no-store", "--quiet", *flags)
    elif command == "pareto":
        code, out, err = run("pareto", path, "--mode", mode, "--points", "2", "--json", "--no-store", *flags)
    else:
        page = tmp_path / "review.html"
        code, out, err = run("report", path, "--mode", mode, "-o", page, "--no-store", *flags)
    if code == 2:
        _named(err)
        assert solved_code == 2 or command == "pareto", f"{command} refused what solve takes: {err}"
        return
    assert code == 0, err
    assert solved_code == 0, f"{command} took what solve refused: {solved}"
    if command == "sweep":
        (point,) = json.loads(out)["points"]
        _verified(point)
        assert point["status"] == solved["status"]
        if solved["status"] == "optimal":
            _design_equal(point["design"], solved["design"])
    elif command == "pareto":
        data = json.loads(out)
        fronts = data.get("fronts") or [data]
        for front in fronts:
            for row in front["rows"]:
                assert row["status"] == "optimal" or front["note"], row["status"]
        lightest = min((front["rows"][0] for front in fronts if front["rows"][0]["status"] == "optimal"),
                       key=lambda row: row["mass"]["value"] if isinstance(row["mass"], dict) else row["mass"],
                       default=None)
        if solved["status"] == "optimal" and solved["objective"]["name"] == "mass":
            assert lightest is not None
            _design_equal(lightest["design"], solved["design"])
    else:
        if solved["status"] not in ("optimal", "unverified"):  # a page without a design says so (review 29)
            assert f"({solved['status']}, no design)" in out and "No design" in page.read_text(encoding="utf-8")
            return
        headline = re.search(r"\((\w+), (\w+) (\S+) ", out)
        assert headline.group(1) == solved["status"]
        assert float(headline.group(3)) == pytest.approx(solved["objective"]["value"], rel=1e-5)
        assert "<svg" in page.read_text(encoding="utf-8")


def test_the_combinations_are_all_there():
    """4 couplings of 2 modes each, 8 aspect combinations, 5 commands (compare once per coupling: it solves every
    mode itself): the count docs/composition.md gives."""
    assert len(ASPECTS) == 8
    assert len(combinations()) == 4 * 8 * (4 * 2 + 1) == 288
