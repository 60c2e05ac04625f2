"""The start-up as a figure: speeds and slip above (in rpm, as cases and sweeps give them), friction torque and
slip power below."""

from __future__ import annotations

import math

import matplotlib
import numpy as np

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

RPM = 30.0 / math.pi  # rpm per rad/s


def literal(text: str) -> str:
    """``text`` (a title, a column name: the user's) as matplotlib is to show it, character for character: each ``$``
    escaped, so that no pair of them starts mathtext (``Fan $\\frac{$ drive`` would not parse)."""
    return text.replace("$", r"\$")


def history_figure(result, title: str = "", nlp: dict | None = None) -> Figure:
    """Speeds and slip above, clutch torque and slip power below; ``nlp``: a solution's ``start_up`` (its NLP
    trajectory, collocation nodes drawn as points over the simulated lines)."""
    h, head = result.history, result.headline
    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(h["t"], h["w_driver"] * RPM, label="driving half")
    top.plot(h["t"], h["w_driven"] * RPM, label="driven half")
    top.plot(h["t"], h["slip"] * RPM, ":", label="slip")
    if nlp is not None:
        path = nlp["trajectory"]
        top.plot(path["t"], np.asarray(path["w_driver"]) * RPM, ".", color="C0", ms=3, label="NLP nodes, driving")
        top.plot(path["t"], np.asarray(path["w_driven"]) * RPM, ".", color="C1", ms=3, label="NLP nodes, driven")
    top.set_ylabel("speed, rpm")
    top.legend(loc="best")
    lines = bottom.plot(h["t"], h["friction_torque"], color="C3", label="clutch torque")
    bottom.set_ylabel("torque, N*m")
    bottom.set_xlabel("time, s")
    power = bottom.twinx()
    lines += power.plot(h["t"], h["power_lost"], color="C4", alpha=0.7, label="slip power (right)")
    power.set_ylabel("slip power, W")
    bottom.legend(handles=lines, loc="best")
    for event in result.events:
        for axis in (top, bottom):
            axis.axvline(event["time"], color="grey", lw=0.8, ls="--")
    headline = (f"t_c = {head['start_time']:.4g} s, L = {head['friction_work']:.4g} J" if head["locks_up"]
                else head["reason"])
    fig.suptitle(f"{literal(title)}\n{headline}" if title else headline, fontsize=10)
    return fig
