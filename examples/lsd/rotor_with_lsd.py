"""A small ROSS rotor on two Type C leaf spring dampers (needs springdyn[ross]).

Run:  python examples/lsd/rotor_with_lsd.py
"""

import numpy as np
import ross as rs

from springdyn.lsd import LSDModel, LSDParameters

# Type C with 20x the passage conductance (leakage_factor) so the rigid-body modes are underdamped
model = LSDModel(LSDParameters.example("C").replace(leakage_factor=20.0))
frequencies = 2 * np.pi * np.linspace(500, 3000, 11) / 60  # rad/s

steel = rs.Material(name="steel_lsd_example", rho=7810, E=211e9, G_s=81.2e9)
shaft = [rs.ShaftElement(0.1, 0.0, 0.08, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True)
         for _ in range(2)]
disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
rotor = rs.Rotor(shaft, [disk], [model.to_ross(0, frequencies, tag="lsd0"), model.to_ross(2, frequencies, tag="lsd1")])
modal = rotor.run_modal(speed=2 * np.pi * 1000 / 60, num_modes=8)
for wn, ld in zip(modal.wn[:4], modal.log_dec[:4]):
    print(f"natural frequency {wn / (2 * np.pi):7.2f} Hz   log decrement {ld:.3f}")
