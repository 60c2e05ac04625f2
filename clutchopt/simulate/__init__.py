"""Start-up simulation of friction couplings (Simionescu & Oproescu, generalised): scenes, effects, closed forms.

``load_scene(path) -> Scene``, ``run_scene(scene) -> SimulationResult`` (``.history`` DataFrame, ``.headline``
dict in SI), ``report_figure(case, solution) -> (Figure | None, caption)``, ``verify(case, solution) -> dict``,
``paper_start_up(J, k, a, M_r, w0) -> {"analytic": ..., "simulated": ...}`` (t_c, L, L_s, lock-up verdict).
Names are imported on first use, so that ``clutchopt`` commands which do not simulate stay quick to start.
"""

from importlib import import_module

_NAMES = {
    "load_scene": "scene", "Scene": "scene", "run_scene": "scene",
    "simulate": "engine", "Model": "engine", "SimulationResult": "engine",
    "report_figure": "design", "verify": "design",
    "paper_start_up": "paper",
}

__all__ = sorted(_NAMES)


def __getattr__(name: str):
    if name not in _NAMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"clutchopt.simulate.{_NAMES[name]}"), name)
