#!/usr/bin/env python3
"""One scene's files in the HCI 4D light field benchmark's submission layout: disp_maps/<scene>.pfm (the centre-view
disparity lfsp depth wrote, already in the benchmark's convention and PFM orientation) and runtimes/<scene>.txt (the
depth command's run time in seconds, from its summary beside the disparity map)."""

import argparse
import json
import shutil
import sys
from pathlib import Path


def write_atomically(path, write):
    """write(temporary) and then rename it to path, so that a killed job leaves no half-written file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(path.name + ".partial")
    write(temporary)
    temporary.replace(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--disparity", required=True, help="lfsp depth's DISP.pfm (DISP.summary.json beside it)")
    parser.add_argument("--pfm", required=True, help="the submission's disp_maps/<scene>.pfm")
    parser.add_argument("--runtime", required=True, help="the submission's runtimes/<scene>.txt")
    args = parser.parse_args()
    disparity = Path(args.disparity)
    summary_path = disparity.with_suffix(".summary.json")
    try:
        summary = json.loads(summary_path.read_text())
        seconds = summary["timings_seconds"]["stage"]
    except (OSError, ValueError, KeyError, TypeError) as error:
        sys.exit(f"hci_submission: {summary_path}: no run time ({error})")
    write_atomically(Path(args.pfm), lambda temporary: shutil.copyfile(disparity, temporary))
    write_atomically(Path(args.runtime), lambda temporary: temporary.write_text(f"{float(seconds):.3f}\n"))


if __name__ == "__main__":
    main()
