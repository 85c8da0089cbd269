"""``camcam laws [--json]``: every law with its exact characteristic values."""

from __future__ import annotations

from camcam.cli.commands import help_of
from camcam.cli.output import print_json
from camcam.motion.catalog import LAWS, make_law

__all__ = ["register", "law_table"]


def register(sub) -> None:
    p = sub.add_parser("laws", help=help_of("laws"))
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def law_table() -> dict[str, dict[str, float]]:
    """Spec name → {"Vm", "Am", "Jmax", "Jmin", …} for every law at its default parameters."""
    return {name: make_law(name).characteristics().as_dict() for name in LAWS}


def run(args) -> int:
    table = law_table()
    if args.json:
        print_json(table)
        return 0
    print(f"{'law':28s} {'Vm':>8s} {'Am':>8s} {'Jmax':>10s} {'Jmin':>10s}  description")
    for name, c in table.items():
        print(f"{name:28s} {c['Vm']:8.4f} {c['Am']:8.4f} {c['Jmax']:10.4f} {c['Jmin']:10.4f}  {LAWS[name].description}")
    return 0
