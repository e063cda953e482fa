#!/usr/bin/env python3
"""The lfsp workflow's index page: one row per capture with its key figures and a link to its report."""

import argparse
import html
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from report import PAGE, figures  # noqa: E402  (the same figures as each capture's page)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--results", required=True, help="the workflow's results folder")
    parser.add_argument("--out", required=True, help="the index page to write")
    parser.add_argument("captures", nargs="+", help="capture names (results sub-folders)")
    args = parser.parse_args()
    results = Path(args.results)
    rows = [figures(results / name, name) for name in args.captures]
    header = "".join(f"<th>{html.escape(k)}</th>" for k in rows[0])
    lines = []
    for name, row in zip(args.captures, rows):
        cells = "".join(f"<td>{html.escape(str(v))}</td>" for k, v in row.items() if k != "capture")
        lines.append(f'<tr><td><a href="{html.escape(name)}/report.html">{html.escape(name)}</a></td>{cells}</tr>')
    body = (f"<h1>lfsp workflow: {len(rows)} captures</h1><p>{html.escape(str(results))}</p>"
            f"<table><tr>{header}</tr>{''.join(lines)}</table>")
    out = Path(args.out)
    temporary = out.with_name(out.name + ".partial")
    temporary.write_text(PAGE.format(title="lfsp workflow", body=body))
    temporary.replace(out)


if __name__ == "__main__":
    main()
