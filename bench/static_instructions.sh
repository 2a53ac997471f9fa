#!/bin/bash
# Instructions per sample of the static engine on the original's example1 workload (the
# queries of bench/static_query.py), counted with valgrind's callgrind: unlike a timing, the
# count does not depend on what else runs on the machine. Needs valgrind.
#   bash bench/static_instructions.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SWIPL="$ROOT/.venv/bin/swipl"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cat > "$WORK/w.pl" <<PL
:- use_module('$ROOT/prolog/ddc.pl').
w(M, N) :- forall(member(V, [1, 2, 3]), ddc:query(true, drawn(1) ~= V, _, [samples(N), program(M)])),
    ddc:expectation(true, g ~= X, X, _, [samples(N), program(M)]).
run(N) :- ddc_load('$ROOT/prolog/examples/example1.pl', M), set_random(seed(7)), w(M, 200), w(M, N).
PL
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$SWIPL" -g "run($1)" -t halt "$WORK/w.pl" 2>&1 \
        | grep -o "Collected : [0-9]*" | grep -o "[0-9]*"
}
a=$(count 10)
b=$(count 5010)
# 4 queries x 5000 more samples
python3 -c "print('instructions per sample: %.0f' % (($b - $a) / 20000))"
