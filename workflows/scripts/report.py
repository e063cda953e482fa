#!/usr/bin/env python3
"""One capture's page of the lfsp workflow: what lfsp decode, depth, segment and evaluate wrote into its folder
(their summaries and preview images), as a self-contained HTML page (images inline)."""

import argparse
import base64
import html
import json
import sys
from pathlib import Path


def load(folder, name):
    path = folder / name
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as error:
        sys.exit(f"report: {path}: {error}")


def image(folder, name, title, shape):
    """An inline PNG, enlarged (views of lenslet decodes are small): `shape` "wide" sets the width, "tall" the height."""
    path = folder / name
    if not path.exists():
        return ""
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return (f'<figure><img class="{shape}" alt="{html.escape(title)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{html.escape(title)}</figcaption></figure>")


def figures(folder, capture):
    """The key figures of one capture, shared by its page and the index (index.py imports this). An input that was
    already a light field (views folder, .h5, .mat) has no decode: its size comes from segment's summary."""
    decoded = load(folder, "decoded.summary.json") if (folder / "decoded.summary.json").exists() else None
    depth = load(folder, "disparity.summary.json")
    segmentation = load(folder, "segmentation.summary.json")
    metrics = load(folder, "metrics.json")["lfsp"]
    if decoded:
        light_field = decoded["light_field"]
        size = f'{light_field["nu"]}x{light_field["nv"]} views of {light_field["width"]}x{light_field["height"]}'
    else:
        size = str(segmentation.get("shape", ""))
    row = {
        "capture": capture,
        "light field": size,
        "white image": decoded["white_image"].get("name", "") if decoded else "(not decoded)",
        "views processed": f'{depth["views"]["n"]}x{depth["views"]["n"]}',
        "disparity range": f'{depth["range"]["min"]:.2f} .. {depth["range"]["max"]:.2f} ({depth["range"].get("source", "")})',
        "superpixels": metrics["labels"],
        "effective label ratio": round(metrics["elr"], 3),
        "compactness": round(metrics["compactness"], 3),
        "decode s": round(decoded["seconds"]["total"], 2) if decoded else "",
        "depth s": round(depth.get("timings_seconds", {}).get("stage", 0.0), 2),
        "segment s": round(segmentation["timings_seconds"].get("command", 0.0), 2),
    }
    if (folder / "depth_metrics.json").exists():  # an HCI scene with ground truth
        scores = load(folder, "depth_metrics.json")["all"]
        row["HCI BadPix 0.07 %"] = round(scores["badpix_0.07"], 2)
        row["HCI MSE x100"] = round(scores["mse_x100"], 3)
    return row


PAGE = """<!doctype html><html><head><meta charset="utf-8"><title>{title}</title><style>
body {{ font-family: sans-serif; margin: 2em auto; max-width: 1100px; background: #fafafa; color: #222; }}
table {{ border-collapse: collapse; }} td, th {{ border: 1px solid #ccc; padding: 4px 10px; text-align: left; }}
figure {{ display: inline-block; margin: 0 1em 1em 0; vertical-align: top; }}
img {{ image-rendering: pixelated; border: 1px solid #999; }} img.wide {{ width: 400px; }} img.tall {{ height: 400px; }}
figcaption {{ font-size: 0.85em; color: #555; }}
</style></head><body>{body}</body></html>
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--capture", required=True, help="the capture file")
    parser.add_argument("--folder", required=True, help="its results folder")
    parser.add_argument("--out", required=True, help="the page to write")
    args = parser.parse_args()
    folder = Path(args.folder)
    rows = "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
                   for k, v in figures(folder, args.capture).items())
    body = (f"<h1>{html.escape(folder.name)}</h1><p>{html.escape(args.capture)} &rarr; {html.escape(str(folder))}</p>"
            f"<table>{rows}</table><h2>Depth and superpixels</h2>"
            + image(folder, "disparity.png", "centre-view disparity (TURBO over the range above)", "wide")
            + image(folder, "segmentation.overlay_centre.png", "LFSP boundaries on the centre view", "wide")
            + image(folder, "segmentation.overlay_epi_h.png", "boundaries on a horizontal EPI", "wide")
            + image(folder, "segmentation.overlay_epi_v.png", "boundaries on a vertical EPI", "tall"))
    out = Path(args.out)
    temporary = out.with_name(out.name + ".partial")
    temporary.write_text(PAGE.format(title=html.escape(folder.name), body=body))
    temporary.replace(out)


if __name__ == "__main__":
    main()
