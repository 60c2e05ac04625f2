"""The layers of clutchopt, bottom to top: a module imports from its own layer and those below, never from one
above, and no imports go round in a circle (tests/test_architecture.py checks both, module- and function-level
imports alike; docs/architecture.md shows the table).

Modules are named within ``clutchopt`` (``__init__`` is the package itself). A module belongs to the layer that
names it or, failing that, its closest package: ``start_up.section`` is named in "start-up", ``start_up.equations``
belongs with its package to "start-up equations" (importing a module runs its packages first, so a package sits as
low as its lowest module).
"""

LAYERS: tuple[tuple[str, str, tuple[str, ...]], ...] = (  # (layer, what it holds, modules)
    ("base", "CasADi-or-float arithmetic, units, input errors, files, the run records' schema, packaged data, "
             "the solver tolerance, environment switches, this table",
     ("__init__", "backend", "units", "unit_table", "errors", "files", "records", "window_records", "data",
      "solver_tolerance", "switches", "layers")),
    ("model", "Quantity, Variable, Constraint, Formulation, SpeedLaw, Coupling; functions declared monotone",
     ("model", "monotone")),
    ("formulations", "one module per coupling: quantities, equations, paper procedure, comparison rows",
     ("formulations",)),
    ("start-up equations", "the [start_up] quantities and the drive's equations, written once for the NLP and the "
                           "simulator", ("start_up", "start_up.equations")),
    ("simulator", "integrators stepped within a budget, friction and motor laws, effects, closed forms, plots (the "
                  "package's public names load on first use)", ("simulate",)),
    ("start-up", "the [start_up] section, the NLP's shape and drive, its collocation and mesh, a design's start "
                 "simulated",
     ("start_up.section", "start_up.drive", "start_up.lining", "start_up.transcription", "start_up.mesh",
      "start_up.simulation")),
    ("case and aspects", "case file -> Case; material library (fill, variants), scatter, case templates, the fields "
                         "the checks across fields read",
     ("cases", "fields_read", "materials", "scatter", "template")),
    ("presentation", "tables, text, HTML and JSON of results, read by their fields; the run store",
     ("output", "store", "store_kept", "store_checkpoint")),
    ("optimise", "posed problem, solve strategies, float64 verdict, start-up check, sweeps, Pareto, robust, "
                 "comparisons, choices", ("optimise",)),
    ("scenes", "start-up scene files (a scene may solve its coupling's case for a design)", ("simulate.scene",)),
    ("report", "the design-review page", ("report",)),
    ("commands", "the command line, its crash files, the benchmarks", ("cli", "__main__", "crash", "bench")),
)
