"""A small ROSS rotor on two Type C leaf spring dampers (needs springdyn[ross]).

1. Modal analysis as ROSS 2.3 does it: the damper coefficients taken at the spin speed
   (``to_ross``: a dense 0-20 000 rpm table that never extrapolates).
2. The same mode with the coefficients at the mode's own frequency
   (``whirl_consistent_mode``): the damper's coefficients depend on the vibration
   frequency, so this is the answer to use.  At 1000 rpm the spin-speed coefficients
   overstate the damping of the 30 Hz mode (log decrement 1.16 against 0.82, with the oil's
   added mass that ``to_ross`` passes as ``mxx``); at 5000 rpm
   the gyroscopic effect splits the modes and mode 0 is the lower (backward) one.

Run:  python examples/lsd/rotor_with_lsd.py
"""

import warnings

import numpy as np

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    try:
        import ross as rs
    except ModuleNotFoundError:
        raise SystemExit(
            "this example needs ROSS: pip install 'springdyn[ross]' (or .venv/bin/pip install -e '.[ross]')"
        ) from None

from springdyn.lsd import LSDModel, LSDParameters, bearing_at_frequency, whirl_consistent_mode

# Type C with 20x the passage conductance (leakage_factor) so the rigid-body modes are underdamped
model = LSDModel(LSDParameters.example("C").replace(leakage_factor=20.0))
steel = rs.Material(name="steel_lsd_example", rho=7810, E=211e9, G_s=81.2e9)


def rotor(b0, b1):
    shaft = [
        rs.ShaftElement(0.1, 0.0, 0.08, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True)
        for _ in range(2)
    ]
    disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
    return rs.Rotor(shaft, [disk], [b0, b1])


tabled = rotor(model.to_ross(0, rpm_range=(0, 20000), tag="lsd0"), model.to_ross(2, rpm_range=(0, 20000), tag="lsd1"))
for spin_rpm in (1000.0, 5000.0):
    modal = tabled.run_modal(speed=2 * np.pi * spin_rpm / 60, num_modes=8)
    print(f"coefficients at the spin speed {spin_rpm:5.0f} rpm:")
    for wn, ld in zip(modal.wn[:2], modal.log_dec[:2]):
        print(f"  natural frequency {wn / (2 * np.pi):7.2f} Hz   log decrement {ld:.3f}")

for spin_rpm in (1000.0, 5000.0):
    wd, modal = whirl_consistent_mode(
        lambda w: rotor(bearing_at_frequency(model, 0, w, tag="a"), bearing_at_frequency(model, 2, w, tag="b")),
        speed=2 * np.pi * spin_rpm / 60,
        omega_guess=2 * np.pi * spin_rpm / 60,
        mode=0,
        num_modes=8,
    )
    print(
        f"coefficients at the mode's own frequency, spin {spin_rpm:5.0f} rpm: damped frequency "
        f"{wd / (2 * np.pi):.2f} Hz, log decrement {modal.log_dec[0]:.3f}"
    )
