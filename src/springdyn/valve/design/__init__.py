"""The design wing: springs designed from requirements, proven across tolerances and life.

- :mod:`.synthesis` -- valve springs from requirements (``[requirements]``): the lightest
  springs that meet load points, space, Goodman, surge and float speed, ranked;
- :mod:`.pack_synthesis` -- the inner spring of a pack for a given outer spring and force
  split (equal stress, the radial clearance kept);
- :mod:`.tolerances` -- a spring across its manufacturing tolerances (``[tolerances]``,
  ``[criteria]``): Sobol or Monte Carlo variants, percentiles, failing shares;
- :mod:`.screening` -- the response surface of a screened tolerance study: which variants it
  must simulate and which the surface judges;
- :mod:`.life` -- relaxation at the service temperature and the life against a load
  spectrum (``[spectrum]``);
- :mod:`.calibrate` -- the drawing's load points against the model, and a fit of the shear
  modulus or the active coils to them, or of the damping to a measured trace;
- :mod:`.criteria` -- the one set of pass/fail criteria (``[criteria]``): every limit and the rule
  that judges it, for the report, the tolerance study and the synthesis.

It imports every wing below it.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "Requirements": "synthesis",
    "read_requirements": "synthesis",
    "synthesize": "synthesis",
    "write_candidates": "synthesis",
    "inner_spring_for": "pack_synthesis",
    "inner_spring_figures": "pack_synthesis",
    "inner_spring_text": "pack_synthesis",
    "pack_file_tables": "pack_synthesis",
    "tolerance_study": "tolerances",
    "read_tolerances": "tolerances",
    "calibrate": "calibrate",
    "calibrate_trace": "calibrate",
    "LoadSpectrum": "life",
    "service_life": "life",
    "Criteria": "criteria",
    "Verdict": "criteria",
    "RULES": "criteria",
    "margin": "criteria",
    "passes": "criteria",
    "spring_verdicts": "criteria",
    "float_verdict": "criteria",
    "pump_up_verdict": "criteria",
    "seating_verdict": "criteria",
    "clearance_verdict": "criteria",
    "MIN_VALVE_PISTON_CLEARANCE": "criteria",
    "MIN_GOODMAN_SAFETY": "criteria",
    "MIN_SURGE_MARGIN": "criteria",
    "FLOAT_MARGIN": "criteria",
    "MAX_SEATING_VELOCITY": "criteria",
    "JUDGING_MODEL": "criteria",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
