#!/usr/bin/env python3
"""The lfsp workflow's index page: one row per capture with its key figures and a link to its report. With
--allow-missing (the workflow's error handler) a capture without a report is listed as failed with its one-line error:
the last line of the log of its first stage that did not finish, or "not run" when none of its jobs ran."""

import argparse
import html
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from report import PAGE, figures  # noqa: E402  (the same figures as each capture's page)

STAGES = (("decode", "decoded.h5"), ("depth", "disparity.pfm"), ("segment", "segmentation.h5"),
          ("report", "report.html"))


def error_line(folder):
    """The one-line error of a capture whose report is missing."""
    for stage, output in STAGES:
        log = folder / "logs" / f"{stage}.log"
        if (folder / output).exists() or not log.exists():
            continue
        lines = [line.strip() for line in log.read_text(errors="replace").splitlines() if line.strip()]
        return f"{stage} failed: {lines[-1]}" if lines else f"{stage} failed (empty log {log})"
    return "not run"


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--results", required=True, help="the workflow's results folder")
    parser.add_argument("--out", required=True, help="the index page to write")
    parser.add_argument("--allow-missing", action="store_true", help="list captures without a report as failed")
    parser.add_argument("captures", nargs="+", help="capture names (results sub-folders)")
    args = parser.parse_args()
    results = Path(args.results)
    rows, failed = {}, {}
    for name in args.captures:
        if args.allow_missing and not (results / name / "report.html").exists():
            failed[name] = error_line(results / name)
        else:
            rows[name] = figures(results / name, name)
    columns = [key for row in rows.values() for key in row if key != "capture"]
    columns = list(dict.fromkeys(columns))
    header = "<th>capture</th>" + "".join(f"<th>{html.escape(k)}</th>" for k in columns)
    lines = []
    for name in args.captures:
        link = f'<a href="{html.escape(name)}/report.html">{html.escape(name)}</a>'
        if name in failed:
            lines.append(f'<tr class="failed"><td>{html.escape(name)}</td>'
                         f'<td colspan="{max(len(columns), 1)}">FAILED: {html.escape(failed[name])}</td></tr>')
        else:
            cells = "".join(f"<td>{html.escape(str(rows[name].get(k, '')))}</td>" for k in columns)
            lines.append(f"<tr><td>{link}</td>{cells}</tr>")
    summary = f"{len(rows)} captures" + (f", {len(failed)} failed" if failed else "")
    body = (f"<h1>lfsp workflow: {summary}</h1><p>{html.escape(str(results))}</p>"
            f"<table><tr>{header}</tr>{''.join(lines)}</table>")
    out = Path(args.out)
    temporary = out.with_name(out.name + ".partial")
    temporary.write_text(PAGE.format(title="lfsp workflow", body=body))
    temporary.replace(out)


if __name__ == "__main__":
    main()
