"""Shared foundations of every model family.

- :mod:`~springdyn.core.units`: pint at the edges, SI floats inside;
- :mod:`~springdyn.core.params`: the parameter base (``param()`` fields, TOML loading
  with validation, ``from_toml``/``from_dict``/``example``/``replace``);
- :mod:`~springdyn.core.results`: the :class:`~springdyn.core.results.Result` base of
  every analysis result (``summary``, ``to_xarray``, ``to_csv``, ``plot``, reprs);
- :mod:`~springdyn.core.io`: atomic CSV/JSON writers and the CSV reader;
- :mod:`~springdyn.core.errors`: :class:`InputError` and :class:`SolverError`;
- :mod:`~springdyn.core.docstrings`: shared parameter descriptions of numpydoc docstrings;
- :mod:`~springdyn.core.plotting`, :mod:`~springdyn.core.progress`.

Nothing here imports numba, xarray or matplotlib at import time.
"""
