"""The `refracta` command line: `refracta demo --out DIR`."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


def demo(out: Path) -> int:
    """Ray fans of the example atmospheres, as PNG files in `out`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from refracta import examples, plot

    out.mkdir(parents=True, exist_ok=True)
    for name, make in examples.ATMOSPHERES.items():
        start = time.perf_counter()
        field, eye, elevations, length = make()
        figure = plot.ray_fan(field, eye, elevations, length, title=f"{name}: {field.type_name}")
        path = out / f"rays_{name}.png"
        figure.savefig(path, dpi=110)
        plt.close(figure)
        print(f"wrote {path} ({time.perf_counter() - start:.2f} s)")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="refracta", description="Physically based mirages.")
    commands = parser.add_subparsers(dest="command", required=True)
    demo_parser = commands.add_parser("demo", help="draw the demo images")
    demo_parser.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    args = parser.parse_args(argv)
    if args.command == "demo":
        return demo(args.out)
    parser.error(f"unknown command {args.command}")
    return 2


if __name__ == "__main__":
    sys.exit(main())
