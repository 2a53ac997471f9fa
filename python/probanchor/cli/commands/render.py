"""`anchoring render SCENARIO --out DIR`: what the simulated camera sees.

Writes one PNG per frame (``frame_0000.png`` ...), ``depth_0000.png`` with ``--depth`` (a
colour map, black where there is no depth), and ``DIR/SCENARIO.gif``; with ``--overlay`` the
percepts' bounding boxes, best categories and colour names are drawn on the GIF frames (and
written as ``overlay_0000.png`` ...).
"""

from __future__ import annotations

import argparse

import numpy as np

from probanchor.cli.options import add_frame_options


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "render", help="render a scenario's camera frames to PNGs and a GIF",
        description=__doc__.split("\n\n")[1] if __doc__ else None)
    add_frame_options(parser)
    parser.add_argument("--no-noise", action="store_true", help="clean frames")
    parser.add_argument("--depth", action="store_true", help="also write depth PNGs")
    parser.add_argument("--overlay", action="store_true",
                        help="draw the percepts (boxes, categories, colours) on the GIF")
    parser.add_argument("--every", type=int, default=1, help="keep every N-th frame")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.set_defaults(func=run)


def depth_png(depth: np.ndarray) -> np.ndarray:
    """Depth as a colour map stretched over the frame's own range (near: red, far: blue)."""
    import cv2

    valid = depth[depth > 0]
    lo, hi = (np.percentile(valid, [1, 99]) if valid.size else (0.0, 1.0))
    scaled = np.clip((depth - lo) / max(hi - lo, 1e-6) * 255, 0, 255).astype(np.uint8)
    coloured = cv2.applyColorMap(255 - scaled, cv2.COLORMAP_JET)[:, :, ::-1]
    coloured[depth <= 0] = 0
    return coloured


def overlay(rgb: np.ndarray, percepts: list) -> np.ndarray:
    import cv2

    out = rgb.copy()
    for p in percepts:
        x0, y0, x1, y1 = p.bbox
        colour = (255, 210, 0) if p.best_category == "skin" else (255, 255, 255)
        cv2.rectangle(out, (x0, y0), (x1 - 1, y1 - 1), colour, 1)
        label = p.best_category
        if p.colour_names and p.best_category != "skin":
            label = f"{p.colour_names[0]} {label}"
        cv2.putText(out, label, (x0, max(y0 - 3, 8)), cv2.FONT_HERSHEY_SIMPLEX, 0.33,
                    (0, 0, 0), 2, cv2.LINE_AA)
        cv2.putText(out, label, (x0, max(y0 - 3, 8)), cv2.FONT_HERSHEY_SIMPLEX, 0.33, colour,
                    1, cv2.LINE_AA)
    return out


def run(args: argparse.Namespace) -> int:
    import imageio.v2 as imageio

    from probanchor.tabletop import Simulation, load_scenario

    scenario = load_scenario(args.scenario)
    args.out.mkdir(parents=True, exist_ok=True)
    pipeline = None
    if args.overlay:
        from probanchor.perception import Pipeline

        pipeline = Pipeline()
    gif_frames = []
    n = 0
    with Simulation(scenario, width=args.width, height=args.height, fps=args.fps,
                    seed=args.seed, noise=not args.no_noise) as sim:
        for frame in sim:
            if frame.index % max(args.every, 1):
                continue
            imageio.imwrite(args.out / f"frame_{frame.index:04d}.png", frame.rgb)
            if args.depth:
                imageio.imwrite(args.out / f"depth_{frame.index:04d}.png",
                                depth_png(frame.depth))
            image = frame.rgb
            if pipeline is not None:
                image = overlay(image, pipeline.process(frame))
                imageio.imwrite(args.out / f"overlay_{frame.index:04d}.png", image)
            gif_frames.append(image)
            n += 1
        fps = sim.fps / max(args.every, 1)
    gif = args.out / f"{scenario.name}.gif"
    imageio.mimsave(gif, gif_frames, duration=1.0 / fps, loop=0)
    print(f"{n} frames ({gif_frames[0].shape[1]}x{gif_frames[0].shape[0]}) in {args.out}, "
          f"animation {gif}")
    return 0
