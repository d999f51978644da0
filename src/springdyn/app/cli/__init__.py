"""The ``springdyn`` command line: a thin layer over the Python API (no physics here).

- :mod:`.main` -- the entry point: the parser, exit codes, one line per outcome;
- :mod:`.common` -- what every family's commands share (outputs, ranges, tables);
- :mod:`.valve`, :mod:`.cfcs`, :mod:`.lsd` -- each family's commands (:mod:`.valve_cam_design`:
  the valve commands that design and check a cam and a lever, ``cam-from-lift``, ``cam-check``
  and ``kinematics``; :mod:`.valve_friction`: ``friction``, the drive torque and friction power;
  :mod:`.valve_clearance`: ``clearance``, the valve-to-piston clearance over speed;
  :mod:`.valve_camshaft`: ``camshaft``, several valves on one twisting camshaft;
  :mod:`.valve_synthesis`: ``synthesize``, ``tolerance`` and ``life``, springs from
  requirements, across their tolerances, relaxed and under a load spectrum;
  :mod:`.valve_options`: the options every valve command shares and the model it builds);
- :mod:`.docs_cmd` -- ``springdyn docs``, the generated references.
"""

import os as _os

# One BLAS thread for the command (set before NumPy loads; an explicit setting wins).
# springdyn's matrices are small, and its sweeps run their own threads: OpenBLAS's own pool
# only spins after each call (measured: 0.15-0.2 s of CPU on a 0.9 s `valve simulate`).
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
