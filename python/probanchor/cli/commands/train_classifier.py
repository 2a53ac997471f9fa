"""`anchoring train-classifier`: train the category classifier on rendered views.

Renders random tables (3-4 objects of the categories ball, bottle, bowl, box, can, cup,
mug), segments them with the pipeline, trains a small MLP on the shape features of 60 % of
the scenes, fits its softmax temperature on 20 %, tests it on the last 20 % and writes the
model (JSON weights) with its held-out accuracy.
"""

from __future__ import annotations

import argparse
from pathlib import Path


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "train-classifier", help="train the category classifier on rendered views",
        description=__doc__.split("\n\n")[1] if __doc__ else None)
    parser.add_argument("--scenes", type=int, default=1200, help="random tables (default 1200)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--hard", type=float, default=0.4,
                        help="share of scenes with a partly hidden or a lifted object "
                             "(default 0.4)")
    parser.add_argument("--out", type=Path, default=None,
                        help="model file (default: the shipped model, "
                             "python/probanchor/perception/models/category_mlp.json)")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from probanchor.learning.classifier_data import build_dataset
    from probanchor.perception.classifier import DEFAULT_MODEL, CategoryModel
    from probanchor.perception.training import train

    previous = CategoryModel.load(DEFAULT_MODEL) if DEFAULT_MODEL.exists() else None
    model, report = train(build_dataset(args.scenes, args.seed, args.hard), args.seed,
                          previous=previous)
    out = args.out or DEFAULT_MODEL
    out.parent.mkdir(parents=True, exist_ok=True)
    model.save(out)
    labels = report["confusion"]["labels"]
    print(f"held-out accuracy {report['held_out_accuracy']:.3f} on {report['test_segments']} "
          f"segments ({report['train_segments']} for training, "
          f"{report['calibration_segments']} for calibration, {report['scenes']} scenes, "
          f"seed {report['seed']})")
    print(f"softmax temperature {report['temperature']:.2f}: held-out log loss "
          f"{report['held_out_nll']:.3f} (uncalibrated {report['held_out_nll_uncalibrated']:.3f}),"
          f" mean top probability {report['mean_top_probability']:.3f}")
    print("confusion (rows: true, columns: predicted)")
    print("        " + " ".join(f"{c:>5}" for c in labels))
    for name, row in zip(labels, report["confusion"]["matrix"], strict=True):
        print(f"{name:>7} " + " ".join(f"{v:>5}" for v in row))
    views = report["held_out_by_view"]
    print("held-out accuracy by view: " + ", ".join(
        f"{k} {v['accuracy']:.3f} ({v['segments']})" for k, v in views.items()))
    if "previous_model" in report:
        old = report["previous_model"]
        print(f"previous model on the same segments: {old['held_out_accuracy']:.3f}; by view: "
              + ", ".join(f"{k} {v['accuracy']:.3f}" for k, v in old["held_out_by_view"].items()))
    print(f"model -> {out}")
    return 0
