"""Every hostile input of tests/hostile_runtime.py through the CLI, judged as tests/test_hostile.py judges its own
(``error:`` lines and exit code 2 with nothing recorded, or exit code 0; never a traceback, an exit code 3 or a
hang); and what a suite of quick runs cannot show: each wait on a Dask server ends at the deadline, and user text
is drawn as it is written."""

import io
import time
from contextlib import nullcontext
from html import escape

import pytest

from clutchopt.cli import EXIT_BAD_INPUT, main
from clutchopt.errors import InputError
from clutchopt.optimise.dask_client import DEADLINE_S, connect
from hostile_runtime import HANDSHAKE, HOSTILE, Served
from test_hostile import run_in_process, server, time_limit

CASE = "cases/wedge_paper.toml"


def test_at_least_40_distinct_hostile_inputs():
    assert len(HOSTILE) >= 40 and len({h.name for h in HOSTILE}) == len(HOSTILE)
    assert {h.argv[0] for h in HOSTILE} >= {"solve", "sweep", "pareto", "report", "simulate", "runs"}


@pytest.mark.parametrize("hostile", HOSTILE, ids=lambda h: h.name)
def test_hostile_runtime_input(hostile, tmp_path, capsys, run_store):
    argv = hostile.write(tmp_path / "input")
    serving = server(*hostile.greetings, hold_s=hostile.hold_s) if isinstance(hostile, Served) else nullcontext("")
    started = time.monotonic()
    with serving as address:
        run_in_process(hostile, [arg.replace("{server}", address) for arg in argv], capsys, run_store)
    if "--dask" in argv:
        assert time.monotonic() - started < DEADLINE_S, "the README promises an answer within 10 s"


# --- Dask: every wait ends at the deadline, however the server stalls ----------------------------------------------
@pytest.mark.parametrize("greetings, said", [
    ((None,), "accepted the connection but sent no Dask greeting within 0.5 s"),
    ((HANDSHAKE[:8],), "announced a greeting of 58 bytes but did not send it within 0.5 s"),
    ((HANDSHAKE[:30],), "announced a greeting of 58 bytes but did not send it within 0.5 s"),
    ((HANDSHAKE, None), "cannot connect to a Dask scheduler at {address} within 0.5 s (TimeoutError"),
    ((HANDSHAKE,), "cannot connect to a Dask scheduler at {address} within 0.5 s (TimeoutError"),
], ids=["silent", "length-then-silence", "half-a-greeting", "handshake-then-silence", "no-answers"])
def test_a_stalling_server_is_given_up_at_the_deadline(greetings, said):
    with server(*greetings, hold_s=60) as address:
        started = time.monotonic()
        with pytest.raises(InputError) as refused:
            connect(address, deadline_s=0.5)
        assert time.monotonic() - started < DEADLINE_S / 2  # its own 0.5 s, not the default 10 s (slack for load)
    assert said.format(address=address) in str(refused.value)


def test_the_command_answers_within_10_s_when_a_server_sends_a_length_then_nothing(capsys):
    with server(HANDSHAKE[:8], hold_s=60) as address, time_limit(30):
        started = time.monotonic()
        code = main(["sweep", CASE, "--vary", "speed=900", "--dask", address])
        assert DEADLINE_S - 1 < time.monotonic() - started < 2 * DEADLINE_S  # one wait to the deadline, not two
    assert code == EXIT_BAD_INPUT
    assert capsys.readouterr().err == (f"error: --dask: {address} is not a Dask scheduler: it accepted the "
                                       "connection but announced a greeting of 58 bytes but did not send it within "
                                       "10 s\n")


# --- user text reaches matplotlib as it is written, never as mathtext ------------------------------------------------
@pytest.mark.parametrize("text", ["Fan $\\frac{$ drive", "a\\$b$ and $", "$$", "$x^2$ costs $5", "\\textbf{x} 100% {",
                                  "$\\sqrt{$ $_$", "<b>$x$</b> & co"])
def test_user_text_is_drawn_as_written(text):
    import matplotlib
    from matplotlib.figure import Figure

    from clutchopt.simulate.plot import literal

    figure = Figure()
    figure.suptitle(literal(text))
    drawn = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "none"}):  # text as text, not as paths
        figure.savefig(drawn, format="svg")
    assert f">{escape(text, quote=False)}</text>" in drawn.getvalue()
