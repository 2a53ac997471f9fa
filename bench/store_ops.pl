/*  store_ops.pl -- what one read or write of a particle's value costs, by representation.

    The filter keeps each particle's values in a hash table of its own
    (prolog/ddc_store.pl); an engine that evaluated clauses over all
    particles at once would keep one column per random variable instead (a
    term with one argument per particle).  This prints nanoseconds per
    operation on this machine for both, in one run:

        .deps/swipl/bin/swipl -O bench/store_ops.pl

    store: a particle's table of 30 keys pos(oI)-5 (as a bench particle
    holds), each read in turn: a hit, a miss, term_hash/2 alone; column:
    arg/3 and nb_setarg/3 on a 1000-argument term; and the loop alone,
    subtracted from each.  Best of 5 repetitions of 900,000 operations.
*/

:- use_module('../prolog/ddc_store').
:- set_prolog_flag(optimise, true).
:- initialization(main, main).

%   Each loop goes 30,000 times through the 30 keys.
loop_empty(0, _, _) :- !.
loop_empty(N, S, Ks) :- empty_keys(Ks, S), N1 is N-1, loop_empty(N1, S, Ks).

empty_keys([], _).
empty_keys([_|Ks], S) :- empty_keys(Ks, S).

loop_hit(0, _, _) :- !.
loop_hit(N, S, Ks) :- hit_keys(Ks, S), N1 is N-1, loop_hit(N1, S, Ks).

hit_keys([], _).
hit_keys([K|Ks], S) :- store_get(S, K, _), hit_keys(Ks, S).

loop_miss(0, _, _) :- !.
loop_miss(N, S, Ks) :- miss_keys(Ks, S), N1 is N-1, loop_miss(N1, S, Ks).

miss_keys([], _).
miss_keys([K|Ks], S) :- \+ store_get(S, K, _), miss_keys(Ks, S).

loop_hash(0, _, _) :- !.
loop_hash(N, S, Ks) :- hash_keys(Ks), N1 is N-1, loop_hash(N1, S, Ks).

hash_keys([]).
hash_keys([K|Ks]) :- term_hash(K, _), hash_keys(Ks).

loop_arg(0, _, _) :- !.
loop_arg(N, C, Is) :- arg_keys(Is, C), N1 is N-1, loop_arg(N1, C, Is).

arg_keys([], _).
arg_keys([I|Is], C) :- arg(I, C, _), arg_keys(Is, C).

loop_setarg(0, _, _) :- !.
loop_setarg(N, C, Is) :- setarg_keys(Is, C), N1 is N-1, loop_setarg(N1, C, Is).

setarg_keys([], _).
setarg_keys([I|Is], C) :- nb_setarg(I, C, 0.5), setarg_keys(Is, C).

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
    ns(loop_empty(N, S, Ks), E),
    ns(loop_hit(N, S, Ks), Hit),
    ns(loop_miss(N, S, Missing), Miss),
    ns(loop_hash(N, S, Ks), Hash),
    ns(loop_arg(N, C, Is), Arg),
    ns(loop_setarg(N, C, Is), SetArg),
    format("ns per operation (loop of ~1f ns subtracted):~n", [E]),
    forall(member(Name-T, [ 'store hit (a particle\'s hash table)'-Hit,
                            'store miss'-Miss,
                            'term_hash/2 of the key alone'-Hash,
                            'column read (arg/3)'-Arg,
                            'column write (nb_setarg/3)'-SetArg ]),
           ( X is T - E, format("  ~w~t~45| ~1f~n", [Name, X]) )),
    R is (Hit - E) / max(Arg - E, 1.0),
    format("store hit / column read: ~1fx~n", [R]).
