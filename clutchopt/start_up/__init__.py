"""The start-up of a coupling on its real drive, in one package (docs/start_up.md).

- ``equations``: the ``[start_up]`` quantities, the effects and the drive's equations, written once for the NLP and
  the simulator;
- ``section``: the ``[start_up]`` section of a case file, read into SI and checked;
- ``transcription``: the start inside the NLP, by Radau collocation;
- ``simulation``: a design's start simulated (solve_ivp), the independent check of the NLP's.

Nothing is imported here: the simulator imports ``equations`` without the rest.
"""
