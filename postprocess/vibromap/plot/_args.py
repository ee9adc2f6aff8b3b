"""The command-line options the picture scripts of vibromap-post share, and their checks: the
image written (-o, --dpi), the slice of a map drawn (--x, --y, --fix) and the periods kept."""

from __future__ import annotations

import argparse
import os

from .._io import parse_fix

DPI_MIN, DPI_MAX = 20, 1200  # below: an unreadable image; above: a picture of gigabytes


def add_image(parser: argparse.ArgumentParser, default: str | None, *, metavar: str = "OUT.png",
              what: str = "image to write") -> None:
    """-o/--output (required when default is None: no name to derive) and --dpi."""
    help_text = f"{what} (default: {default})" if default else what
    parser.add_argument("-o", "--output", metavar=metavar, required=default is None, help=help_text)
    parser.add_argument("--dpi", type=int, default=150,
                        help=f"resolution, dots per inch, {DPI_MIN} to {DPI_MAX} (default: 150)")  # fmt: skip


def add_slice(parser: argparse.ArgumentParser, *, x: str, y: str, fix: str) -> None:
    """--x, --y and --fix NAME=VALUE ...: the map axes drawn and where the others are held."""
    parser.add_argument("--x", metavar="AXIS", help=x)
    parser.add_argument("--y", metavar="AXIS", help=y)
    parser.add_argument("--fix", metavar="NAME=VALUE", nargs="+", action="extend", default=[], help=fix)


def add_periods(parser: argparse.ArgumentParser, help_text: str) -> None:
    parser.add_argument("--periods", metavar="N", type=float, help=help_text)


def finish(parser: argparse.ArgumentParser, argv: list[str] | None, source: str | None = None,
           suffix: str = ".png") -> argparse.Namespace:
    """Parses argv and checks what add_* added: --fix into args.fixed {name: value}, --dpi in its
    range, --periods positive; a missing -o becomes the input `source` (an attribute's name) with
    its extension replaced by `suffix`."""
    args = parser.parse_args(argv)
    if hasattr(args, "fix"):
        try:
            args.fixed = parse_fix(args.fix)
        except ValueError as exc:
            parser.error(str(exc))
    if not DPI_MIN <= args.dpi <= DPI_MAX:
        parser.error(f"--dpi {args.dpi}: must be from {DPI_MIN} to {DPI_MAX}")
    if getattr(args, "periods", None) is not None and not args.periods > 0:
        parser.error("--periods must be positive")
    if args.output is None and source is not None:
        args.output = os.path.splitext(getattr(args, source))[0] + suffix
    return args
