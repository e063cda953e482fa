#!/usr/bin/env python3
"""Decode a lenslet capture, estimate depth, segment it into light-field superpixels, score both against the
simulator's ground truth and save a figure of the centre view, the depth and the superpixel boundaries.

    PYTHONPATH=build/python python3 examples/decode_depth_segment.py samples/mini-illum --out mini-illum.png

The folder is what `lfsp simulate` writes: capture.LFR (or capture.lfp), whites/, ground_truth/decoded.h5.
"""

import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import numpy

import lfsp


def boundaries(labels: numpy.ndarray) -> numpy.ndarray:
    """Pixels whose right or lower neighbour has another label."""
    edge = numpy.zeros(labels.shape, dtype=bool)
    edge[:, :-1] |= labels[:, :-1] != labels[:, 1:]
    edge[:-1, :] |= labels[:-1, :] != labels[1:, :]
    return edge


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("simulation", help="folder written by `lfsp simulate` (capture, whites/, ground_truth/)")
    parser.add_argument("--out", default="decode_depth_segment.png", help="the figure (PNG)")
    parser.add_argument("--size", type=int, default=12, help="superpixel size, pixels (default: 12)")
    args = parser.parse_args()

    captures = sorted(glob.glob(os.path.join(args.simulation, "capture.*")))
    if not captures:
        print(f"{args.simulation}: no capture.* in it", file=sys.stderr)
        return 2
    light_field = lfsp.decode(captures[0])
    truth = lfsp.read(os.path.join(args.simulation, "ground_truth", "decoded.h5"))

    disparity, _ = lfsp.depth(light_field)
    labels = lfsp.segment(light_field, disparity, size=args.size)
    depth_scores = lfsp.evaluate_depth(disparity, truth.disparity)
    nv, nu = labels.shape[:2]
    central = (truth.labels.shape[0] - nv) // 2  # the truth covers every view; the labels the well-lit ones
    truth_labels = truth.labels[central : central + nv, central : central + nu]
    scores = lfsp.evaluate_segmentation(labels, gt_labels=truth_labels, gt_disparity=truth.disparity, no_refocus=True)

    print(f"light field: {light_field}")
    print(f"depth: BadPix 0.07 {depth_scores['all']['badpix_0.07']:.1f} %, MSE x100 {depth_scores['all']['mse_x100']:.2f}")
    lfsp_scores = scores["lfsp"]
    print(
        f"superpixels: {lfsp_scores['labels']}, boundary recall {lfsp_scores['boundary_recall']:.3f}, "
        f"under-segmentation error {lfsp_scores['undersegmentation_error']:.4f}, "
        f"self-similarity {lfsp_scores['self_similarity']:.3f} px "
        f"(ground truth's own: {lfsp_scores['self_similarity_reference']:.3f} px)"
    )

    centre_view = light_field.samples[light_field.shape[0] // 2, light_field.shape[1] // 2]
    centre_labels = labels[nv // 2, nu // 2]
    overlay = numpy.clip(centre_view, 0.0, 1.0).copy()
    overlay[boundaries(centre_labels)] = (1.0, 0.2, 0.1)

    figure, axes = plt.subplots(1, 3, figsize=(12, 4.2), constrained_layout=True)
    axes[0].imshow(numpy.clip(centre_view, 0.0, 1.0))
    axes[0].set_title("centre view (decoded)")
    shown = axes[1].imshow(disparity, cmap="viridis")
    axes[1].set_title(f"disparity (BadPix 0.07: {depth_scores['all']['badpix_0.07']:.1f} %)")
    figure.colorbar(shown, ax=axes[1], label="px per view step", shrink=0.8)
    axes[2].imshow(overlay)
    axes[2].set_title(f"{lfsp_scores['labels']} light-field superpixels")
    for axis in axes:
        axis.set_axis_off()
    figure.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
