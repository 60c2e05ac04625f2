"""Data shipped with clutchopt: the material library and the starting values of `clutchopt init`."""
