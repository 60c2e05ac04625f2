"""The start-up of a coupling on its real drive, in one package (docs/start_up.md).

- ``equations``: the ``[start_up]`` quantities, the effects and the drive's equations, written once for the NLP and
  the simulator;
- ``overload``: the largest torque the coupling passes (top speed, worn linings, highest friction) and what it must
  slip below: the motor's breakdown torque, the machine's max_transmitted_torque;
- ``section``: the ``[start_up]`` section of a case file, read into SI and checked;
- ``drive``: the shape of a start's NLP, the drive's equations at a design, the start's requirements as named
  constraints;
- ``transcription``: the start inside the NLP, by Radau collocation; ``mesh``: its intervals, graded, then adapted;
- ``simulation``: a design's start simulated (SciPy's integrators), the independent check of the NLP's
  (``clutchopt.optimise.start_up_check`` compares them).

Nothing is imported here: the simulator imports ``equations`` without the rest.
"""
