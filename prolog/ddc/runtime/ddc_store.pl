/*  ddc_store.pl -- the per-world store of the DDC system.

    A world (one sample of the static engine, one particle of the filter)
    records every random variable it has sampled, every memoised derived
    atom and every fact asserted into it.  The store must survive
    backtracking (a variable sampled inside \+ or a failed branch stays
    sampled: each random variable is drawn at most once per world), so it is
    a hash table updated with nb_setarg/3 and nb_linkarg/3: an insertion
    copies only the new entry, never the chain or the table.
*/

:- module(ddc_store,
          [ store_new/1,            % -Store
            store_new/2,            % -Store, +Indexed
            store_get/3,            % +Store, +Key, -Value
            store_put/3,            % +Store, +Key, +Value
            store_delete/2,         % +Store, +Key
            store_entries/2,        % +Store, -Pairs
            store_match/3,          % +Store, ?Key, -Value   (non-ground key: scan)
            store_prune/3,          % +Store, +MinTime, +DropKeys (in place)
            store_size/2            % +Store, -Count
          ]).

/** <module> Non-backtrackable hash table for DDC worlds

A store is a record store(Count, Data, Indexed) (fields count, data and
indexed); Data is a list of Key-Value while Count =< 8, else Buckets =
b(L1, ..., Ln), each Li unbound (empty) or a list of Key-Value.  Keys
must be ground.  Indexed (true or false): whether keys X-Time are also
indexed by functor and time (store_put/3), in entries '$by'(Name/Arity,
Time) -> ix(Xs) (record ix, field keys).
*/

%   Arithmetic compiled inline (local to this file; see ddc.pl).
:- set_prolog_flag(optimise, true).

:- use_module(library(aggregate)).
:- use_module(library(lists)).
:- use_module('../lang/ddc_records').

:- record_type store(count, data, indexed).
:- record_type ix(keys).

%   Small stores (up to 8 entries) are a list of Key-Value in argument 2;
%   larger ones a bucket term b(L1, ..., Ln).

%!  store_new(-Store) is det.
%
%   An empty indexed store (store_new(Store, true)).
store_new(S) :-
    store_new(S, true).

%!  store_new(-Store, +Indexed) is det.
%
%   An empty store; Indexed true: keys X-Time are indexed by X's functor
%   and the time (see store_put/3), which pays in a store that non-ground
%   reads search and costs an index entry per insertion in one that they
%   do not (a small store is scanned as fast).
store_new(store(0, [], Ix), Ix) :-
    must_be(boolean, Ix).

%!  store_get(+Store, +Key, -Value) is semidet.
store_get(Store, K, V) :-
    store_data(Store, D),
    (   D = [_|_]
    ->  memberchk(K-V0, D)
    ;   D \== [],
        term_hash(K, H),
        functor(D, _, S),
        I is H mod S + 1,
        arg(I, D, L),
        nonvar(L),
        memberchk(K-V0, L)
    ),
    V = V0.

%!  store_put(+Store, +Key, +Value) is det.
%
%   Adds Key-Value (Key must not be present; the engine checks first).
%   In an indexed store, keys X-Time with a compound X and an integer Time
%   are also indexed by X's functor and the time (entry '$by'(Name/Arity,
%   Time) -> ix(Xs)), so that store_match/3 with a partly bound X reads
%   only those keys instead of the whole table.
store_put(T, K, V) :-
    put_(T, K, V),
    (   store_indexed(T, true), K = X-Tm, compound(X), integer(Tm)
    ->  functor(X, N, A),
        (   store_get(T, '$by'(N/A, Tm), Cell)
        ->  ix_keys(Cell, Xs),
            duplicate_term(X, X1),      % (as set_entries/3)
            nb_link_ix_keys(Cell, [X1|Xs])
        ;   put_(T, '$by'(N/A, Tm), ix([X]))
        )
    ;   true
    ).

put_(T, K, V) :-
    store_count(T, C),
    store_data(T, D),
    (   D = [_|_]
    ->  (   C >= 8
        ->  functor(B, b, 16),
            forall(member(K0-V0, [K-V|D]), bucket_put(B, K0, V0)),
            nb_set_store_data(T, B)
        ;   set_data_entries(T, [K-V|D])
        ),
        C1 is C + 1,
        nb_set_store_count(T, C1)
    ;   D == []
    ->  set_data_entries(T, [K-V]),
        nb_set_store_count(T, 1)
    ;   bucket_put(D, K, V),
        C1 is C + 1,
        nb_set_store_count(T, C1),
        functor(D, _, S),
        (   C1 > 2*S -> grow(T) ; true )
    ).

%!  store_delete(+Store, +Key) is det.
%
%   Removes Key's entry (if any), in place.  (A key X-Time stays in the
%   index of its functor and time; store_match/3 skips it.)
store_delete(T, K) :-
    store_count(T, C),
    store_data(T, D),
    (   D = [_|_]
    ->  (   select_kv(D, K, D1)
        ->  nb_set_store_data(T, D1),
            C1 is C-1,
            nb_set_store_count(T, C1)
        ;   true
        )
    ;   D == []
    ->  true
    ;   term_hash(K, H),
        functor(D, _, S),
        I is H mod S + 1,
        arg(I, D, L),
        (   nonvar(L), select_kv(L, K, L1)
        ->  (   L1 == [] -> nb_setarg(I, D, _) ; nb_setarg(I, D, L1) ),
            C1 is C-1,
            nb_set_store_count(T, C1)
        ;   true
        )
    ).

select_kv([K0-V|T], K, Rest) :-
    (   K0 == K
    ->  Rest = T
    ;   Rest = [K0-V|Rest1],
        select_kv(T, K, Rest1)
    ).

bucket_put(B, K, V) :-
    term_hash(K, H),
    functor(B, _, S),
    I is H mod S + 1,
    arg(I, B, L),
    (   var(L) -> set_entries(I, B, [K-V]) ; set_entries(I, B, [K-V|L]) ).

%   set_entries(+I, +Buckets, +[K-V|Rest]): non-backtrackable assignment
%   of bucket I, a chain whose Rest is already held by the store.  Only the new entry is
%   copied (it may share bindings that backtracking would undo); the new cell
%   that joins it to Rest is linked (nb_linkarg/3 freezes the global stack as
%   nb_setarg/3 does, and the cell holds no variable): an insertion copies
%   one entry instead of the whole chain.
set_entries(I, T, [KV|Rest]) :-
    duplicate_term(KV, E),
    nb_linkarg(I, T, [E|Rest]).

%   set_data_entries(+Store, +[K-V|Rest]): the same for a small store's
%   list of entries.
set_data_entries(T, [KV|Rest]) :-
    duplicate_term(KV, E),
    nb_link_store_data(T, [E|Rest]).

grow(T) :-
    store_data(T, B),
    functor(B, _, S),
    S2 is S*4,
    functor(B2, b, S2),
    forall(( arg(_, B, L), nonvar(L), member(K-V, L) ), bucket_put(B2, K, V)),
    nb_set_store_data(T, B2).

%!  store_entries(+Store, -Pairs) is det.
store_entries(T, Pairs) :-
    findall(K-V, store_match(T, K, V), Pairs).

%!  store_match(+Store, ?Key, -Value) is nondet.
%
%   Enumerates the entries whose key unifies with Key (through the index
%   for a key X-Time with a compound X and an integer time, else a scan; the
%   index entries themselves are never enumerated).
store_match(T, K, V) :-
    store_indexed(T, true), nonvar(K), K = X-Tm, compound(X), integer(Tm), !,
    functor(X, N, A),
    store_get(T, '$by'(N/A, Tm), ix(Xs)),
    member(X, Xs),
    store_get(T, X-Tm, V).
store_match(T, K, V) :-
    store_data(T, D),
    (   D = [_|_]
    ->  member(K-V, D)
    ;   compound(D),
        arg(_, D, L),
        nonvar(L),
        member(K-V, L)
    ),
    \+ K = '$by'(_, _).

%!  store_size(+Store, -Count) is det.
store_size(T, C) :-
    aggregate_all(count, store_match(T, _, _), C).

%!  store_prune(+Store, +MinTime, +DropKeys) is det.
%
%   In place: removes the entries whose key has a time below MinTime (keys
%   X-T, '$memo'(G, T), '$mat'(S, T), '$w'(X, T), '$swept'(I, T) with an
%   integer T) and those whose key is in DropKeys.  The particle filter
%   runs it at every step.
store_prune(T, MinT, Drop) :-
    store_data(T, D),
    (   D == []
    ->  true
    ;   D = [_|_]
    ->  prune_list(D, MinT, Drop, D1, 0, C),
        nb_set_store_data(T, D1),
        nb_set_store_count(T, C)
    ;   functor(D, _, S),
        prune_buckets(1, S, D, MinT, Drop, 0, C),
        nb_set_store_count(T, C)
    ).

prune_buckets(I, S, B, MinT, Drop, C0, C) :-
    (   I > S
    ->  C = C0
    ;   arg(I, B, L),
        (   var(L)
        ->  C1 = C0
        ;   prune_list(L, MinT, Drop, L1, C0, C1),
            (   L1 == L -> true
            ;   L1 == [] -> nb_setarg(I, B, _)
            ;   nb_setarg(I, B, L1)
            )
        ),
        I1 is I+1,
        prune_buckets(I1, S, B, MinT, Drop, C1, C)
    ).

prune_list([], _, _, [], C, C).
prune_list([E|Es], MinT, Drop, Out, C0, C) :-
    E = K-_,
    (   key_time(K, T), T < MinT
    ->  Out = Out1, C1 = C0
    ;   Drop \== [], memberchk(K, Drop)
    ->  Out = Out1, C1 = C0
    ;   Out = [E|Out1], C1 is C0+1
    ),
    prune_list(Es, MinT, Drop, Out1, C1, C).

key_time(_-T, T) :- integer(T), !.
key_time('$memo'(_, T), T) :- integer(T), !.
key_time('$mat'(_, T), T) :- integer(T), !.
key_time('$w'(_, T), T) :- integer(T), !.
key_time('$swept'(_, T), T) :- integer(T), !.
key_time('$plan'(T), T) :- integer(T), !.
key_time('$moved'(T), T) :- integer(T), !.
key_time('$by'(_, T), T) :- integer(T).
