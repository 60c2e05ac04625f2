"""``clutchopt simulate SCENE [--json] [--plot out.png]``."""

from __future__ import annotations

import math

from clutchopt.cli.options import FIGURE_SUFFIXES, Checked, add_json_option, add_parser, add_store_options, path, \
    record_simulation, recording

_LINES = (
    ("start_time", "start time t_c", "s"),
    ("friction_work", "friction work L", "J"),
    ("source_work", "work into the clutch L_s", "J"),
    ("peak_slip_power", "peak slip power", "W"),
    ("temperature_rise", "temperature rise", "K"),
    ("total_friction_work", "friction work, whole run", "J"),
    ("end_time", "end of the run", "s"),
)


def add_command(commands) -> None:
    parser = add_parser(
        commands, "simulate", "simulate a start-up: speeds, clutch torque, lock-up time and friction work",
        "A scene (TOML) names the clutch (a design or a friction law), the driven machine and the effects to\n"
        "include (motor curve, springs, gravity, fan load, ...); docs/simulate.md describes them. Where the\n"
        "paper's transient has a closed form, the headline figures are printed beside it.",
        ("clutchopt simulate cases/scenes/paper_transient.toml",
         "clutchopt simulate cases/scenes/wedge_motor_springs.toml --plot startup.png"))
    parser.add_argument("scene", help="the scene file (TOML, e.g. cases/scenes/paper_transient.toml)")
    add_json_option(parser)
    parser.add_argument("--plot", action=Checked, check=path, metavar="FILE",
                        help="also draw speeds (rpm), clutch torque and slip power over time into FILE (.png, .svg, "
                             ".pdf)")
    add_store_options(parser)
    parser.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.files import check_output, write_whole
    from clutchopt.output import SIMULATION_UNITS, to_json, with_units
    from clutchopt.simulate import load_scene, run_scene
    from clutchopt.simulate.analytic import PaperTransient

    scene = load_scene(args.scene)
    if args.plot:
        check_output("--plot", args.plot, FIGURE_SUFFIXES)
    with recording(args) as store:
        result = run_scene(scene)
        if args.plot:
            from clutchopt.simulate.plot import history_figure  # (matplotlib: 0.4-0.5 s, only for a figure asked for)

            write_whole("--plot", args.plot, lambda path: history_figure(result, scene.title).savefig(path, dpi=120))
        record_simulation(store, scene, result)  # (once the figure is written: review 25)
    analytic = None
    m = scene.model
    if m.law.name == "paper" and m.load.constant and "motor_curve" not in m.effects:
        analytic = PaperTransient(m.inertia, m.law.k, m.law.a, m.load.torque, m.driver_speed).summary()
    if args.json:
        return to_json(with_units({"scene": scene.path, "title": scene.title, **result.as_dict(),
                                   **({"analytic": analytic} if analytic else {})}, SIMULATION_UNITS))
    return _text(scene, result, analytic) + (f"\nfigure written to {args.plot}" if args.plot else "")


def _text(scene, result, analytic) -> str:
    from clutchopt.records import lock_up_verdict

    h = result.headline
    lines = [scene.title or scene.path, f"effects: {', '.join(h['effects'])}"]
    source = h.get("source", {})
    if source.get("law") == "centrifugal":
        lines.append(f"coupling: {source['coupling']} design ({source['design']}), torque at design speed "
                     f"{source['design_torque']:.6g} N*m, engagement speed {source['engagement_speed']:.6g} rad/s")
        if source.get("from_the_case"):
            lines.append("from the case: " + ", ".join(
                taken["field"] + (f" {taken['value']:.6g} {taken['unit']}".rstrip() if "value" in taken else "")
                for taken in source["from_the_case"]))
        if source.get("over_the_case"):
            lines.append(f"the scene's, not the case's: {', '.join(source['over_the_case'])}")
    if source.get("unread"):
        lines.append(f"unread (their effects not listed): {', '.join(source['unread'])}")
    lines.append(f"lock-up: {lock_up_verdict(h)}" + (f" - {h['reason']}" if not h["locks_up"] else ""))
    for key, label, unit in _LINES:
        if key in h and math.isfinite(h[key]):
            row = f"  {label:<28} {h[key]:.10g} {unit}"
            if analytic and key in analytic and math.isfinite(analytic[key]):
                row += f"   (closed form {analytic[key]:.10g}, {h[key] / analytic[key] - 1:+.1e})"
            lines.append(row)
    for event in result.events:
        lines.append(f"  event at {event['time']:.6g} s: {event['event']}")
    return "\n".join(lines)
