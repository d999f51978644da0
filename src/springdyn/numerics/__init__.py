"""Numerical pieces shared by the model families.

- :mod:`~springdyn.numerics.jit` -- the one decorator of every compiled kernel: a disk cache
  keyed on every source file a kernel is compiled from, never fatal, and the one-line
  notice while an engine compiles;
- :mod:`~springdyn.numerics.erk` -- the compiled embedded Runge-Kutta pairs (Dormand-Prince
  5(4), Bogacki-Shampine 3(2), Tsitouras 5(4)) with dense output and step-size control.
"""
