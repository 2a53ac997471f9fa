"""`anchoring learn-theory`: the theory of occlusion with rules learned from experience.

    anchoring learn-theory DATA.pl [MORE.pl ...] [--out prolog/too_learned.pl] [--seed S]
                           [--plots DIR] [--base prolog/too/] [--json]

Learns the occluder rule (may O start hiding A?) and the tracking rule (does the occlusion go
on?) as one distributional logic tree for ``occluder(A, O):t+1`` (``ddc learn``) and writes the
complete theory: the learned rules, the motion and carrying parameters fitted from the samples
`anchoring collect` writes beside DATA.pl (DATA.motion.json), the affordances read from the data,
and the hand-written parts included from prolog/too/ (too_base.pl: the vocabulary and the
filter's frame; too_learned_glue.pl: how the learned rule is used; too_motion.pl: carrying and
the motion of hidden objects).
``--out`` is replaced only once the new theory loads. ``--plots DIR`` draws the tree and
P(occluder | distance) beside the paper's and the original system's, and writes the table of the
learned coefficients beside theirs, and the learned parameters beside the hand-written ones
(DIR/<name>_parameters.md).
"""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    parser = sub.add_parser("learn-theory", help="learn the theory of occlusion from data",
                            description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("data", type=Path, nargs="+", help="data from `anchoring collect`")
    parser.add_argument("--out", type=Path, default=Path("prolog/too_learned.pl"),
                        help="the theory to write (default prolog/too_learned.pl)")
    parser.add_argument("--base", type=Path, default=None, metavar="DIR",
                        help="the folder of the hand-written parts the theory includes "
                             "(too_base.pl, too_learned_glue.pl, too_motion.pl and, for the "
                             "table, too_parameters.pl; default prolog/too/)")
    parser.add_argument("--seed", type=int, default=0, help="the learner's seed (default 0)")
    parser.add_argument("--plots", type=Path, default=None, metavar="DIR",
                        help="write DIR/<name>_tree.png, DIR/<name>_distance.png and "
                             "DIR/<name>_coefficients.md (the heaviest logistic leaves beside "
                             "the paper's)")
    parser.add_argument("--root-model", choices=("auto", "always", "never"), default="never",
                        help="the learner's root model (a regression over every root feature "
                             "that every leaf reads; default never: each draw in the filter "
                             "would compute every feature, 1.5x the CPU of a plain tree)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from probanchor.ddclearn import SearchOptions
    from probanchor.learning.learned_theory import learn_theory, plot_theory

    command = "anchoring " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    result = learn_theory(args.data, args.out, seed=args.seed,
                          base=args.base, command=command,
                          options=SearchOptions(root_model=args.root_model),
                          progress=not args.json and sys.stderr.isatty())
    target = result.result.targets[0]
    pictures = plot_theory(result, args.plots, args.out.stem) if args.plots else []
    figures = {"out": str(result.out), "clauses": target.clauses,
               "groundings": target.groundings, "seconds": round(target.seconds, 2),
               "log_likelihood": target.log_likelihood, "pictures": [str(p) for p in pictures],
               "onset_reach": result.reach.reach if result.reach else None,
               "parameters": {p.name: p.value for p in result.parameters or []},
               "logistic_leaves": result.logistic,
               "release": None if result.release is None else {
                   "clauses": result.release.targets[0].clauses,
                   "groundings": result.release.targets[0].groundings,
                   "log_likelihood": result.release.targets[0].log_likelihood}}
    if args.json:
        print(json.dumps(figures))
        return 0
    print(f"{target.clauses} clauses for {target.name} from {target.groundings} groundings in "
          f"{target.seconds:.1f} s: wrote {result.out}"
          + (f" and {', '.join(map(str, pictures))}" if pictures else ""))
    return 0
