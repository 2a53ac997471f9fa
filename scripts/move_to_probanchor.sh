#!/usr/bin/env bash
# One-off (issue 18): move the top-level packages app, bags, cli, ddclearn, evaluation, jobs,
# perception, percepts, rgbd, tabletop, visualise under one package, probanchor, and rewrite
# the imports and module strings that name them in the code (not its docstrings and comments),
# and the module references and python/... paths in the documentation and pyproject.toml.
#
#   scripts/move_to_probanchor.sh            # git mv + rewrite every file below
#   scripts/move_to_probanchor.sh --sed FILE...   # only the rewrite, on the files given
#                                                  (e.g. files that changed meanwhile)
set -euo pipefail
cd "$(dirname "$0")/.."
P='app|bags|cli|ddclearn|evaluation|jobs|perception|percepts|rgbd|tabletop|visualise'

# import lines, "module.strings" (entry points, patch targets, -m), "python" / "<package>",
# files("<package>") and importorskip("<package>"), a test's top-level package name check
rewrite_python() {
  sed -E -i \
    -e "s/^(\s*(>>> )?)(from|import) ($P)(\.[A-Za-z_][A-Za-z0-9_.]*)?( |$)/\1\3 probanchor.\4\5\6/" \
    -e "s/([\"'])($P)\.([A-Za-z_])/\1probanchor.\2.\3/g" \
    -e "s#\"python\" / \"($P)\"#\"python\" / \"probanchor\" / \"\1\"#g" \
    -e "s/(files|importorskip)\(\"($P)\"\)/\1(\"probanchor.\2\")/g" \
    -e "s/^(\s*)(.*) (if m)\.split\(\"\.\"\)\[0\] == \"($P)\"(.*)$/\1\2\n\1    \3.split(\".\")[:2] == [\"probanchor\", \"\4\"]\5/" \
    "$@"
}

# documentation, pyproject.toml, setup.sh: import lines of examples, "module.strings",
# `module` references (ddclearn.x also bare), python/<package> paths, python -m <package>
rewrite_text() {
  sed -E -i \
    -e "s/^(\s*(>>> )?)(from|import) ($P)(\.[A-Za-z_][A-Za-z0-9_.]*)?( |$)/\1\3 probanchor.\4\5\6/" \
    -e "s/([ (])(ddclearn)\.([a-z_])/\1probanchor.\2.\3/g" \
    -e "s/([\"'])($P)\.([A-Za-z_])/\1probanchor.\2.\3/g" \
    -e "s/(\`~?)($P)(\.[a-z_])/\1probanchor.\2\3/g" \
    -e "s#(^|[^/A-Za-z_.])python/($P)\b#\1python/probanchor/\2#g" \
    -e "s/-m ($P)\b/-m probanchor.\1/g" \
    "$@"
}

rewrite() {
  local py=() text=() f
  for f in "$@"; do
    case "$f" in
      *.py) py+=("$f") ;;
      *) text+=("$f") ;;
    esac
  done
  [ ${#py[@]} -eq 0 ] || rewrite_python "${py[@]}"
  [ ${#text[@]} -eq 0 ] || rewrite_text "${text[@]}"
  # the moved imports now sort after anchoring/bridge: let ruff put each import block in order
  [ ${#py[@]} -eq 0 ] || .venv/bin/ruff check -q --select I --fix "${py[@]}" >/dev/null || true
}

if [ "${1:-}" = "--sed" ]; then
  shift
  rewrite "$@"
  exit 0
fi

mkdir -p python/probanchor
for p in ${P//|/ }; do
  git mv "python/$p" "python/probanchor/$p"
done
cat > python/probanchor/__init__.py <<'EOF'
"""Probabilistic anchoring: everything but the anchoring core and the Prolog bridge.

The subpackages: ``app`` (the loop that wires perception, anchoring and reasoning; runs,
experiments, data collection), ``cli`` (the ``anchoring`` and ``ddc`` commands), ``percepts``
(the percept record and its streams), ``tabletop`` (the simulated table), ``perception`` (RGB-D
frames to percepts), ``rgbd``, ``bags`` (RGB-D bags), ``evaluation``, ``visualise``,
``ddclearn`` (learning DDC programs), ``jobs`` (many independent jobs). The top-level packages
``anchoring`` (percepts in, anchors out) and ``bridge`` (the only door to Prolog) stand apart.

Importing this package imports nothing else.
"""
EOF
git add python/probanchor/__init__.py

mapfile -t files < <(git ls-files -- 'python/*.py' 'tests/*.py' 'bench/*.py' 'scripts/*.py' \
                       'docs/*.md' README.md pyproject.toml scripts/setup.sh Makefile)
rewrite "${files[@]}"
# the moved modules' own folder is one level deeper (the next commit finds these files as
# package resources instead)
mapfile -t moved < <(git grep -l 'Path(__file__).resolve().parents\[' -- python/probanchor)
sed -E -i -e 's/(Path\(__file__\)\.resolve\(\)\.parents)\[3\]/\1[4]/' \
          -e 's/(Path\(__file__\)\.resolve\(\)\.parents)\[2\]/\1[3]/' "${moved[@]}"
git add -A python tests bench scripts docs README.md pyproject.toml Makefile
