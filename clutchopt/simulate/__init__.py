"""Start-up simulation of friction couplings (Simionescu & Oproescu, generalised): scenes, effects, closed forms.

``load_scene(path) -> Scene``, ``run_scene(scene) -> SimulationResult`` (``.history`` DataFrame, ``.headline``
dict in SI), ``report_figure(case, solution) -> (Figure | None, caption)``, ``verify(case, solution) -> dict``,
``paper_start_up(J, k, a, M_r, w0) -> {"analytic": ..., "simulated": ...}`` (t_c, L, L_s, lock-up verdict).
Names are imported on first use, so that ``clutchopt`` commands which do not simulate stay quick to start.
"""

from importlib import import_module

_NAMES = {
    "load_scene": "simulate.scene", "Scene": "simulate.scene", "run_scene": "simulate.scene",
    "simulate": "simulate.engine", "Model": "simulate.engine", "SimulationResult": "simulate.engine",
    "report_figure": "start_up.simulation", "verify": "start_up.simulation",
    "paper_start_up": "simulate.paper",
}

__all__ = sorted(_NAMES)


def __getattr__(name: str):
    if name not in _NAMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"clutchopt.{_NAMES[name]}"), name)
