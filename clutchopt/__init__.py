"""clutchopt: size centrifugal clutches and couplings by constrained optimisation."""

__version__ = "0.1.0"
