/*  store_ops.pl -- what one read or write of a particle's value costs, by representation.

    The filter keeps each particle's values in a hash table of its own
    (prolog/ddc/runtime/ddc_store.pl); an engine that evaluated clauses over all
    particles at once would keep one column per random variable instead (a
    term with one argument per particle).  This prints nanoseconds per
    operation on this machine for both, in one run:

        .venv/bin/swipl -O bench/store_ops.pl

    store: a particle's table of 30 keys pos(oI)-5 (as a bench particle
    holds), each read in turn: a hit, a miss, term_hash/2 alone; column:
    arg/3 and nb_setarg/3 on a 1000-argument term; and the loop alone,
    subtracted from each.  Best of 5 repetitions of 900,000 operations.
*/

:- use_module('../prolog/ddc/runtime/ddc_store').
:- set_prolog_flag(optimise, true).
:- initialization(main, main).

%   run(+N, +Op, +Table, +Keys): N times Op on each of Keys in turn.  Every
%   operation, the empty one too, is one indexed call of operation/3, so that
%   subtracting the empty loop leaves the operation's own cost.
run(0, _, _, _) :- !.
run(N, Op, T, Ks) :- keys(Ks, Op, T), N1 is N-1, run(N1, Op, T, Ks).

keys([], _, _).
keys([K|Ks], Op, T) :- operation(Op, T, K), keys(Ks, Op, T).

operation(empty, _, _).
operation(hit, S, K) :- store_get(S, K, _).
operation(miss, S, K) :- \+ store_get(S, K, _).
operation(hash, _, K) :- term_hash(K, _).
operation(arg, C, I) :- arg(I, C, _).
operation(setarg, C, I) :- nb_setarg(I, C, 0.5).

%   ns(+Goal, -Ns): best of 5 runs of Goal (900,000 operations), in ns
%   per operation.
ns(Goal, Ns) :-
    findall(T, ( between(1, 5, _),
                 statistics(cputime, T0), call(Goal), statistics(cputime, T1),
                 T is (T1 - T0) * 1.0e9 / 900000 ), Ts),
    min_list(Ts, Ns).

main(_) :-
    store_new(S, false),
    forall(between(1, 30, I), store_put(S, pos(o(I))-5, (0.1, 0.2, 0.3))),
    functor(C, col, 1000),
    forall(between(1, 1000, I), nb_setarg(I, C, 0.0)),
    N = 30000,
    findall(pos(o(I))-5, between(1, 30, I), Ks),
    findall(seen(o(I))-5, between(1, 30, I), Missing),
    findall(I, between(1, 30, I), Is0),
    maplist([I, J]>>(J is I*31), Is0, Is),
    ns(run(N, empty, S, Ks), E),
    ns(run(N, hit, S, Ks), Hit),
    ns(run(N, miss, S, Missing), Miss),
    ns(run(N, hash, S, Ks), Hash),
    ns(run(N, arg, C, Is), Arg),
    ns(run(N, setarg, C, Is), SetArg),
    format("ns per operation (the empty loop's ~1f ns subtracted):~n", [E]),
    forall(member(Name-T, [ 'store hit (a particle\'s hash table)'-Hit,
                            'store miss'-Miss,
                            'term_hash/2 of the key alone'-Hash,
                            'column read (arg/3)'-Arg,
                            'column write (nb_setarg/3)'-SetArg ]),
           ( X is T - E, format("  ~w~t~45| ~1f~n", [Name, X]) )),
    R is (Hit - E) / max(Arg - E, 1.0),
    format("store hit / column read: ~1fx~n", [R]).
