"""``springdyn valve ...`` commands (thin layer over :mod:`springdyn.valve`)."""

from __future__ import annotations

from ..cli.common import add_output_options, print_json, print_table, quantity
from ..units import format_quantity
from .spring import ValveSpring

__all__ = ["register"]

#: Display units of the internal parameters in the human-readable table.
PARAM_UNITS = {
    "K": ("N/m", "N/mm", "contact stiffness of a coil"),
    "K1": ("N/m", "N/mm", "spring rate at free length"),
    "K2": ("N/m", "N/mm", "spring rate at set-up length"),
    "K3": ("N/m", "N/mm", "stiffened rate 1.15 K2"),
    "Kh1": ("N/m", "N/mm", "chain element Kh1"),
    "Kh2": ("N/m", "N/mm", "chain element Kh2"),
    "Ks": ("N/m", "N/mm", "low-pitch element Ks"),
    "m1": ("kg", "g", "chain mass m1"),
    "m2": ("kg", "g", "chain mass m2"),
    "me": ("kg", "g", "end mass me"),
    "M": ("kg", "g", "spring mass"),
    "f1": ("Hz", "Hz", "surge frequency, free length"),
    "f2": ("Hz", "Hz", "surge frequency, set-up length"),
    "n1p": ("", "", "pitch term n1'"),
    "n2p": ("", "", "pitch term n2'"),
    "Pc": ("m", "mm", "coil gap term"),
    "Lc": ("m", "mm", "solid length"),
    "Fset": ("N", "N", "set-up force"),
    "F1": ("N", "N", "first nonlinear force"),
    "F2": ("N", "N", "second nonlinear force"),
    "Fcon": ("N", "N", "coil-contact force"),
    "C0": ("N*s/m", "N*s/m", "element damping C0"),
}


def register(sub) -> None:
    valve = sub.add_parser("valve", help="valve springs: MMS Type C multi-mass model")
    vsub = valve.add_subparsers(dest="valve_command", metavar="COMMAND", required=True)

    p = vsub.add_parser("params", help="internal parameters and model variables")
    p.add_argument("spring", metavar="SPRING.toml")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_params)

    p = vsub.add_parser("curve", help="static force and tangent stiffness vs spring length")
    p.add_argument("spring", metavar="SPRING.toml")
    p.add_argument("--from", dest="start", metavar="L1", help="first length (default: free length)")
    p.add_argument("--to", dest="stop", metavar="L2", help="last length (default: where the force is 3 Fcon)")
    p.add_argument("--points", type=int, default=400, metavar="N", help="number of lengths (default 400)")
    add_output_options(p, json=False)
    p.set_defaults(func=cmd_curve)

    p = vsub.add_parser("modes", help="natural frequencies of the chain linearised at a length")
    p.add_argument("spring", metavar="SPRING.toml")
    p.add_argument("--length", required=True, metavar="L", help="spring length, e.g. 38mm")
    p.add_argument("--count", type=int, default=5, metavar="N", help="how many modes (1-5, default 5)")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_modes)

    p = vsub.add_parser("design", help="index, corrected stress, surge frequency at installed/open/coil-contact length")
    p.add_argument("spring", metavar="SPRING.toml")
    p.add_argument("--lift", metavar="LIFT", help="maximum valve lift, e.g. 9mm")
    p.add_argument("--cam-rpm", metavar="RPM", help="camshaft speed for the surge margin (bare number: rpm)")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_design)


def _spring(args) -> ValveSpring:
    return ValveSpring.from_toml(args.spring)


def cmd_params(args) -> int:
    spring = _spring(args)
    params = spring.internal_parameters()
    if args.json:
        print_json(params)
        return 0
    rows = []
    for key, value in params.items():
        unit, display, doc = PARAM_UNITS[key]
        rows.append((key, format_quantity(value, unit, display), doc))
    print(f"{args.spring}: {spring.type} valve spring, MMS Type C")
    print_table(rows, headers=("parameter", "value", "meaning"))
    return 0


def cmd_curve(args) -> int:
    spring = _spring(args)
    start = quantity(args.start, "m", "--from") if args.start is not None else None
    stop = quantity(args.stop, "m", "--to") if args.stop is not None else None
    curve = spring.static_curve(start, stop, args.points)
    if args.csv:
        curve.to_csv(args.csv)
    if args.plot:
        curve.plot(args.plot)
    if not args.csv:
        step = max(1, len(curve.length) // 20)
        rows = [
            (f"{l * 1e3:.3f}", f"{f:.2f}", f"{k / 1e3:.2f}")
            for l, f, k in zip(curve.length[::step], curve.force[::step], curve.stiffness[::step])
        ]
        print_table(rows, headers=("length [mm]", "force [N]", "stiffness [N/mm]"))
    return 0


def cmd_modes(args) -> int:
    spring = _spring(args)
    length = quantity(args.length, "m", "--length")
    freqs = spring.modes(length, args.count)
    force = float(spring.static_force(length))
    if args.json:
        print_json({"length_m": length, "force_N": force, "frequencies_Hz": list(freqs)})
    else:
        print(f"length {length * 1e3:.3f} mm, static force {force:.2f} N")
        print_table([(str(i + 1), f"{f:.2f}") for i, f in enumerate(freqs)], headers=("mode", "frequency [Hz]"))
    return 0


def cmd_design(args) -> int:
    spring = _spring(args)
    lift = quantity(args.lift, "m", "--lift") if args.lift is not None else None
    rpm = quantity(args.cam_rpm, "rad/s", "--cam-rpm", bare_unit="rpm") * 60 / (2 * 3.141592653589793) if args.cam_rpm else None
    fig = spring.design_figures(lift=lift, cam_rpm=rpm)
    if args.json:
        print_json(fig)
        return 0
    print(f"spring index C = {fig['spring_index']:.3f}, Bergstraesser k = {fig['bergstraesser_factor']:.4f}, "
          f"Wahl k = {fig['wahl_factor']:.4f}")
    print(f"solid length Lc = {fig['solid_length_m'] * 1e3:.3f} mm, spring mass M = {fig['spring_mass_kg'] * 1e3:.2f} g")
    rows = []
    for state in ("installed", "open", "coil_contact"):
        if state in fig:
            s = fig[state]
            rows.append((state, f"{s['length_m'] * 1e3:.3f}", f"{s['force_N']:.1f}", f"{s['shear_stress_Pa'] / 1e6:.0f}",
                         f"{s['surge_frequency_Hz']:.1f}", f"{s['surge_margin']:.2f}" if "surge_margin" in s else "-"))
    print_table(rows, headers=("state", "length [mm]", "force [N]", "stress [MPa]", "surge [Hz]", "surge margin"))
    return 0
