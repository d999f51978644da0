"""The cam wing: the lobe, checked and designed before any spring meets it.

- :mod:`.definition` -- :class:`Cam`: lift laws and measured lift tables (``[cam]``);
- :mod:`.analysis` -- the cam checked first: lift, velocity, acceleration, jerk, timing at
  check heights, lobe centre, ramps;
- :mod:`.checks` -- the cam designer's checks: radius of curvature and undercut, flat-tappet
  contact excursion, pressure angle, Hertz stress, the cam's profile;
- :mod:`.from_lift` -- the lobe a wanted valve lift or a cam card (``[cam_card]``) needs
  through the train, with lash ramps;
- :mod:`.timing` -- the ``[timing]`` table: cam angles as crank angles from TDC, cam and
  engine speeds;
- :mod:`.follower` -- the follower at the cam: flat face or roller, its materials and
  allowable contact stress (``[follower]``).

It imports only the engine below it.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "Cam": "definition",
    "Timing": "timing",
    "crank_axis": "timing",
    "Follower": "follower",
    "analyse_cam": "analysis",
    "check_cam": "checks",
    "CamCard": "from_lift",
    "cam_from_valve_lift": "from_lift",
    "cam_from_card": "from_lift",
    "read_valve_lift_table": "from_lift",
    "write_cam": "from_lift",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
