/*  ddc_store.pl -- the per-world store of the DDC engine.

    A world (one sample of the static engine, one particle of the filter)
    records every random variable it has sampled, every memoised derived
    atom and every fact asserted into it.  The store must survive
    backtracking (a variable sampled inside \+ or a failed branch stays
    sampled: each random variable is drawn at most once per world), so it is
    a hash table updated with nb_setarg/3: an insertion copies only the
    entry and its (short) bucket chain, never the whole table.
*/

:- module(ddc_store,
          [ store_new/1,            % -Store
            store_get/3,            % +Store, +Key, -Value
            store_put/3,            % +Store, +Key, +Value
            store_entries/2,        % +Store, -Pairs
            store_match/3,          % +Store, ?Key, -Value   (non-ground key: scan)
            store_filter/3,         % +Store, :Keep, -NewStore
            store_size/2            % +Store, -Count
          ]).

/** <module> Non-backtrackable hash table for DDC worlds

Store = tbl(Count, Buckets); Buckets = b(L1, ..., Ln), each Li unbound
(empty) or a list of Key-Value.  Keys must be ground.
*/

:- meta_predicate store_filter(+, 2, -).

%!  store_new(-Store) is det.
store_new(tbl(0, B)) :-
    functor(B, b, 16).

%!  store_get(+Store, +Key, -Value) is semidet.
store_get(tbl(_, B), K, V) :-
    term_hash(K, H),
    functor(B, _, S),
    I is H mod S + 1,
    arg(I, B, L),
    nonvar(L),
    memberchk(K-V0, L),
    V = V0.

%!  store_put(+Store, +Key, +Value) is det.
%
%   Adds Key-Value (Key must not be present; the engine checks first).
store_put(T, K, V) :-
    T = tbl(C, B),
    term_hash(K, H),
    functor(B, _, S),
    I is H mod S + 1,
    arg(I, B, L),
    (   var(L) -> nb_setarg(I, B, [K-V]) ; nb_setarg(I, B, [K-V|L]) ),
    C1 is C + 1,
    nb_setarg(1, T, C1),
    (   C1 > 2*S -> grow(T) ; true ).

grow(T) :-
    T = tbl(_, B),
    functor(B, _, S),
    S2 is S*4,
    functor(B2, b, S2),
    forall(( arg(_, B, L), nonvar(L), member(K-V, L) ),
           ( term_hash(K, H), I is H mod S2 + 1, arg(I, B2, L2),
             ( var(L2) -> nb_setarg(I, B2, [K-V]) ; nb_setarg(I, B2, [K-V|L2]) ) )),
    nb_setarg(2, T, B2).

%!  store_entries(+Store, -Pairs) is det.
store_entries(tbl(_, B), Pairs) :-
    findall(K-V, ( arg(_, B, L), nonvar(L), member(K-V, L) ), Pairs).

%!  store_match(+Store, ?Key, -Value) is nondet.
%
%   Enumerates the entries whose key unifies with Key (a scan).
store_match(tbl(_, B), K, V) :-
    arg(_, B, L),
    nonvar(L),
    member(K-V, L).

%!  store_size(+Store, -Count) is det.
store_size(tbl(C, _), C).

%!  store_filter(+Store, :Keep, -New) is det.
%
%   New holds the entries K-V of Store for which call(Keep, K, V) succeeds.
store_filter(T, Keep, New) :-
    store_new(New),
    forall(( store_match(T, K, V), call(Keep, K, V) ), store_put(New, K, V)).
