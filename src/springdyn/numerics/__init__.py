"""Numerical engines shared by the model families (compiled Dormand-Prince 5(4))."""
