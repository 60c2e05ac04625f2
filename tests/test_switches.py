"""Environment switches are on or off, or refused by name (clutchopt/switches.py): ``CLUTCHOPT_BUILD_LATER=no`` had
started background builds, since only ``0`` was read as off."""

import pytest

import clutchopt.optimise.compiled as compiled
import clutchopt.optimise.start_up_compiled as later
from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.optimise.problem import Problem, case_formulation
from clutchopt.switches import BUILD_LATER_ENV, switch
from conftest import CASES
from tests.composition import run

ON = ["1", "true", "TRUE", "yes", "Yes", "on", " on "]
OFF = ["0", "false", "False", "no", "NO", "off", " 0 ", ""]


@pytest.mark.parametrize("text, on", [*((t, True) for t in ON), *((t, False) for t in OFF)])
def test_a_switch_reads_each_spelling_of_on_and_off(text, on, monkeypatch):
    monkeypatch.setenv(BUILD_LATER_ENV, text)
    assert switch(BUILD_LATER_ENV) is on


def test_an_unset_switch_takes_its_default(monkeypatch):
    monkeypatch.delenv(BUILD_LATER_ENV, raising=False)
    assert switch(BUILD_LATER_ENV) is True  # background builds on, unless the environment says off


@pytest.mark.parametrize("text", ["2", "maybe", "nein", "0.0"])
def test_a_value_neither_on_nor_off_is_refused_by_name(text, monkeypatch):
    monkeypatch.setenv(BUILD_LATER_ENV, text)
    with pytest.raises(InputError) as error:
        switch(BUILD_LATER_ENV)
    assert error.value.field == "$CLUTCHOPT_BUILD_LATER" and repr(text) in error.value.problem


def test_the_command_line_refuses_a_bad_switch_before_any_solve(monkeypatch):
    monkeypatch.setenv(BUILD_LATER_ENV, "maybe")
    code, out, err = run("solve", CASES / "wedge_paper.toml", "--no-store")
    assert code == 2 and out == ""
    assert err == ("error: $CLUTCHOPT_BUILD_LATER: must be on (1, true, yes, on) or off (0, false, no, off, or "
                   "empty), got 'maybe'\n")


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (no build would start either way)")
@pytest.mark.parametrize("text", ["no", "false", "off"])
def test_no_build_is_started_where_the_switch_is_off_in_words(text, monkeypatch, tmp_path):
    # as tests/test_start_up_compiled.py's "0": the C generated at once (GENERATE_AFTER_S 0), no build started
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(BUILD_LATER_ENV, text)
    monkeypatch.setattr(later, "_STARTED", {})
    monkeypatch.setattr(later, "GENERATE_AFTER_S", 0.0)
    started = []
    monkeypatch.setattr(later, "build_detached", lambda source: started.append(source))
    case = load_case(CASES / "wedge_paper.toml")
    problem = Problem(case_formulation(case))
    assert later.compiled_when_ready(problem.posed) is False
    assert started == [] and problem.posed.library is None
