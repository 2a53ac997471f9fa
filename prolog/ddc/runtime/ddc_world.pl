/*  ddc_world.pl -- the world runtime of the DDC system.

    Part of the DDC system (ddc.pl is the module users load).  A world is
    one sample of a static query or one particle of the filter: it holds
    the values drawn so far.  This module holds what compiled program
    clauses call at run time (reading, sampling and weighing random
    variables, memoised and shared derived atoms, the facts of a filter
    step) and the sweep that samples a world's next time slice.
*/

:- module(ddc_world,
          [ new_world/5,                % +Module, +Time, +Frozen, +Evidence, -World
            new_world/6,                % +Module, +Time, +Frozen, +Evidence, +Check, -World
            new_shared/3,               % +Share, +Threads, -Shared
            world_time_goal/3,          % ?World, ?Time, -Goal
            static_world/1,             % !World
            group_facts/2,              % +Facts, -Groups
            weigh_key/5,                % +X, +T, +Value, !World, +Accumulator
            with_shared/1,              % :Goal
            overlap_checked_worlds/1,   % -N
            sweep/2,                    % !World, +T
            sweep_kind/2,               % +Kind, +T
            plan_sweep/3,               % +Module, +Shared, +T
            needs_eval/1,               % +Dist
            eval_dist/2,                % +Dist0, -Dist
            '$read'/4,                  % +X, +T, ?V, !World
            read_key/4,                 % +X, +T, ?V, !World
            '$read_ev'/4,               % +X, +T, +A, !World
            '$read_q'/4,                % +X, +T, ?V, !World
            '$live'/2,                  % +World, +T
            '$frozen_at'/2,             % +World, +T
            '$clause_error'/3,          % +World, +Id, +Cause
            '$fact'/2,                  % +World, ?Goal
            '$undefined'/2,             % +World, ?Goal
            '$memo'/3,                  % !World, +Goal, :Call
            '$shared'/3,                % +Key, ?Template, :Goal
            '$mat'/3,                   % !World, ?Goal, +T
            '$range'/3,                 % +Lo, +Hi, -List
            range_/3,                   % +Lo, +Hi, -List (integers)
            '$range_bounds'/4,          % +Lo, +Hi, -Lo1, -Hi1
            '$flip'/1,                  % +P
            '$sample_inline'/2          % +Dist, -X
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module('../lang/ddc_records').
:- use_module('../lang/ddc_dist').
:- use_module(ddc_store).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

/** <module> The world runtime of the DDC system

A world is the record

    world(Store, Module, Time, Frozen, Evidence, LogWeight, DensityDims,
          QueryLogWeight, QueryDensityDims, Accumulator, Mode, Facts,
          CheckOverlaps, Shared, Pure)

  - store: the world's own values (ddc_store.pl), module: the program's.
  - time: the current time `t`; frozen: times =< Frozen are no longer
    derivable from earlier ones (the filter's past), -1 for static queries.
  - evidence: (X-T)-Value pairs weighted instead of sampled.
  - log_weight, density_dims: the evidence's log weight and the number of
    density (not mass) factors in it; query_log_weight,
    query_density_dims: the same for a query's weighted literals.
  - accumulator: evidence or query, the weight that likelihood weighting
    currently adds to.
  - mode: normal or sweep (non-ground reads enumerate recorded values only).
  - facts: Name/Arity-[Fact, ...] groups of the facts asserted into the
    world, or static (a static query: no facts).
  - check_overlaps: true if overlapping clauses are checked in this world
    (the first overlap_checked_worlds/1 samples of a query, the first
    overlap_checked_particles/1 particles of each filter step; a check
    proves the later clauses' bodies, so it is not done in every world).
  - shared: none, or (a particle, during a filter step or query) the
    values all particles agree on, a record shared(Store, ImpureKeys,
    RawKeys, Enabled, SettledSteps, Threads) (see "Shared values" below).
  - pure: true while the value being computed has read nothing of this
    world's own and drawn nothing (false outside the filter).
*/

:- record_type world(store, module, time, frozen, evidence, log_weight, density_dims,
                     query_log_weight, query_density_dims, accumulator, mode, facts,
                     check_overlaps, shared, pure).

%   The values all particles agree on (see "Shared values" below) and the
%   keys some particle holds a value of its own for: store, the shared
%   values; impure_keys, the keys held per particle; raw_keys, the untimed
%   copies of this step's observations; enabled false: only the
%   observations are shared (filter_new/5 option share(false));
%   settled_steps: how many steps were settled (ddc_particles.pl,
%   step_particles/9); threads: the groups a step is split into.
:- record_type shared(store, impure_keys, raw_keys, enabled, settled_steps, threads).

%!  world_time_goal(?World, ?Time, -Goal) is det.
%
%   Goal reads World's time into Time: arg/3 itself, for the compiled
%   clauses of a program (asserted, so not goal-expanded as the accessor
%   world_time/2 of this file is).
world_time_goal(W, T, arg(I, W, T)) :-
    world_fields(Fields),
    nth1(I, Fields, time), !.

%!  new_shared(+Share:boolean, +Threads:integer, -Shared) is det.
new_shared(Share, K, shared(Shared, Impure, [], Share, 0, K)) :-
    store_new(Shared),
    store_new(Impure).

%!  overlap_checked_worlds(-N) is det.
%
%   Overlapping clauses are looked for in the first N sampled worlds of a
%   query (and in the first overlap_checked_particles/1 particles of every
%   filter step, ddc_pool.pl): a check proves the later clauses' bodies,
%   too dear for every world.
overlap_checked_worlds(200).

%!  new_world(+Module, +Time, +Frozen, +Evidence, -World) is det.
%!  new_world(+Module, +Time, +Frozen, +Evidence, +Check, -World) is det.
new_world(M, Time, Frozen, Ev, W) :-
    new_world(M, Time, Frozen, Ev, true, W).

new_world(M, Time, Frozen, Ev, Check, W) :-
    store_new(S),
    W = world(S, M, Time, Frozen, Ev, 0.0, 0, 0.0, 0, evidence, normal, [], Check, none, false).

/*  Shared values.  In a filter many values are the same in every particle:
    a value computed only from facts, observations and other shared values,
    with a deterministic distribution (val/1), is the same wherever it is
    computed.  Such a value is computed once per step, in whichever
    particle needs it first, and kept in the filter's shared store instead
    of every particle's own; other particles find it there.  A theory in
    which a perceived object's position is a val/1 of its observation (too.pl)
    then spends per-particle work only on what the particles disagree on.

    Each computation of a key (a random variable, a memoised or
    materialised derived atom) starts with Pure = true; reading a key from
    the world's own store, a non-ground read, a draw from a distribution
    other than val/1, or a likelihood weighting makes it false (the
    observations' values are in the shared store).  A pure value goes to
    the shared store unless the key is in ImpureKeys (some particle
    computed it from its own values, so the particles may differ), an
    impure one to the world's own store and ImpureKeys.  So a key is either shared or in the particles' own stores,
    never both, and a value read from the shared store is the value every
    particle would have computed.  A pure computation draws no random
    number, so sharing changes neither the draws nor any value: the
    particles are bit for bit those of computing everything in every
    particle (tests/prolog/test_ddc_shared.pl compares the two).  The
    weight an observation adds is shared the same way (key '$w'(X, T)), and
    so is a whole transition clause whose keys were all shared
    ('$swept'(Id, T), the sweep skips it).  At the end of a step, a value
    that all particles hold on their own but that came out the same in
    every one (an object seen again: wherever each particle had it, it is
    now where it was seen) moves to the shared store (ddc_particles.pl,
    share_agreed/5).
    Outside the filter (static queries) there is no shared store. */

%   known(+W, +K, -V): K's value in W, from its own store (which makes the
%   computation in progress impure) or the shared store.
known(W, K, V) :-
    world_store(W, S),
    (   store_get(S, K, V0)
    ->  world_pure(W, P),
        (   P == false -> true ; nb_set_world_pure(W, false) ),
        V = V0
    ;   world_shared(W, Sh),
        Sh \== none,
        shared_store(Sh, SS),
        store_get(SS, K, V)
    ).

%   shared_known(+W, +K): K is in W's shared store.
shared_known(W, K) :-
    world_shared(W, Sh),
    Sh \== none,
    shared_store(Sh, SS),
    store_get(SS, K, _).

impure(W) :-
    world_pure(W, P),
    (   P == false -> true ; nb_set_world_pure(W, false) ).

%   begin_value(+W, -P0) ... end_value(+W, +P0, +K, +V): around the
%   computation of key K's value V; records it (shared or own, see above).
begin_value(W, P0) :-
    world_pure(W, P0),
    nb_set_world_pure(W, true).

end_value(W, P0, K, V) :-
    world_shared(W, Sh),
    (   Sh == none
    ->  world_store(W, S),
        store_put(S, K, V),
        nb_set_world_pure(W, false)
    ;   world_pure(W, P),
        shared_impure_keys(Sh, Imp),
        (   P == true, shared_enabled(Sh, true), \+ store_get(Imp, K, _)
        ->  shared_store(Sh, SS),
            store_put(SS, K, V),
            nb_set_world_pure(W, P0)
        ;   world_store(W, S),
            store_put(S, K, V),
            (   store_get(Imp, K, _) -> true ; store_put(Imp, K, true) ),
            nb_set_world_pure(W, false)
        )
    ).

'$live'(W, T) :-
    world_frozen(W, Frozen),
    T > Frozen.

'$frozen_at'(W, T) :-
    world_frozen(W, Frozen),
    T =< Frozen.

%!  '$read'(+X, +T, ?V, +W) is nondet.
%
%   V is the value of random variable X at time T (u: untimed) in W.
'$read'(X, T, V, W) :-
    (   ground(X)
    ->  read_key(X, T, V, W)
    ;   read_enum(X, T, V, W)
    ).

read_key(X, T, V, W) :-
    world_store(W, S),
    (   store_get(S, X-T, Val)          % known/3, inline
    ->  world_pure(W, P),
        (   P == false -> true ; nb_set_world_pure(W, false) ),
        Val \== '$undef'
    ;   world_shared(W, Sh), Sh \== none,
        shared_store(Sh, SS), store_get(SS, X-T, Val)
    ->  Val \== '$undef'
    ;   world_evidence(W, Ev),                  % not yet read: evidence, or sampled
        (   Ev \== [], memberchk((X-T)-EV, Ev)
        ->  weigh_key(X, T, EV, W, evidence),
            Val = EV
        ;   sample_key(X, T, W, Val)
        )
    ),
    (   Val = V -> true                 % match/2, inline
    ;   number(Val), number(V), Val =:= V
    ).

match(Val, V) :-
    (   Val = V -> true
    ;   number(Val), number(V), Val =:= V
    ).

sample_key(X, T, W, Val) :-
    world_shared(W, Sh),
    (   Sh == none                      % outside a filter: every value is the world's own
    ->  world_module(W, M),
        world_store(W, S),
        (   M:'$rv'(X, T, W, 0, none, Out, Tier, Id, R)
        ->  (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
            draw(Out, W, Val),
            store_put(S, X-T, Val)
        ;   store_put(S, X-T, '$undef'),
            fail
        )
    ;   sample_shared(X, T, W, Val)
    ).

sample_shared(X, T, W, Val) :-
    world_module(W, M),
    begin_value(W, P0),
    (   M:'$rv'(X, T, W, 0, none, Out, Tier, Id, R)
    ->  (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
        (   deterministic(Out) -> true ; impure(W) ),
        draw(Out, W, Val),
        end_value(W, P0, X-T, Val)
    ;   end_value(W, P0, X-T, '$undef'),
        fail
    ).

deterministic(val(_)).
deterministic('$chk'(D, _)) :- nonvar(D), D = val(_).

%   Checking for overlapping clauses proves the rivals' bodies; what they
%   read does not make the value impure (it does not depend on them).
check_rivals(false, _, _, _, _, _, _) :- !.
check_rivals(true, M, X, T, W, Tier, Id) :-
    (   world_check_overlaps(W, true)
    ->  world_pure(W, P),
        (   M:'$rv'(X, T, W, Id, none, _, Tier, Id2, _)
        ->  nb_set_world_pure(W, P),
            clause_where(M, Id2, Where2),
            key_term(X, T, K),
            '$clause_error'(W, Id, overlapping_clauses(K, Where2))
        ;   nb_set_world_pure(W, P)
        )
    ;   true
    ).

key_term(X, u, X) :- !.
key_term(X, T, X:T).

draw('$chk'(D, Id), W, V) :- !,
    (   fast_valid(D)
    ->  dist_sample(D, V)
    ;   cheap_check(D)
    ->  checked(D, Id, W),
        dist_sample(D, V)
    ;   catch(dist_sample(D, V0), E, true),
        (   var(E), nonvar(V0) -> V = V0
        ;   checked(D, Id, W),          % throws the distribution's own error
            (   var(E) -> V = V0 ; throw(E) )
        )
    ).
draw(D, _, V) :-
    dist_sample(D, V).

%   Parameters are checked before each draw, except for the multivariate
%   Gaussians, whose check (a Cholesky factorisation) is the sampler's own
%   work: those are checked only when sampling raises an error.
cheap_check(D) :-
    (   var(D) -> true ; \+ expensive_check(D) ).    % unbound: checked/3 raises

%   Parameters valid by construction (a common case, tested inline).  A
%   distribution left unbound by its clause's body is not valid (checked/3
%   names the clause).
fast_valid(D) :- var(D), !, fail.
fast_valid(uniform(S)) :-
    (   S = A:C, integer(A), integer(C) -> C >= A
    ;   is_list(S), S \== []
    ).
fast_valid(val(_)).

expensive_check(gaussian(M, _)) :- is_list(M).
expensive_check(indepGaussians(_)).

checked(D, Id, W) :-
    var(D), !,
    '$clause_error'(W, Id, unbound_distribution).
checked(D, Id, W) :-
    catch(dist_check(D), error(ddc_distribution(D1, Why), _),
          '$clause_error'(W, Id, distribution(D1, Why))).

%!  weigh_key(+X, +T, +Value, !W, +Accumulator) is semidet.
%
%   Likelihood weighting of X-T = Value into W's log weight of the
%   evidence or of the query (Accumulator).  In a filter step (evidence) a
%   weight computed from shared values only is
%   shared: kept as '$w'(X, T) -> w(LogDensity, Dim) (or none: no clause).
%   A weighting makes the computation that needed it impure.
weigh_key(X, T, V, W, Acc) :-
    world_shared(W, Sh),
    (   Sh == none
    ->  weigh_own(X, T, V, W, Acc)
    ;   weigh_key_shared(X, T, V, W, Acc, Sh)
    ).

%   (Outside a filter.)
weigh_own(X, T, V, W, Acc) :-
    world_store(W, S),
    (   weigh_clause(X, T, V, W, Acc, LP, K)
    ->  store_put(S, X-T, V),
        add_weight(W, Acc, LP, K)
    ;   store_put(S, X-T, '$undef'),
        fail
    ).

weigh_key_shared(X, T, V, W, Acc, Sh) :-
    world_store(W, S),
    (   Acc == evidence, shared_store(Sh, SS), store_get(SS, '$w'(X, T), Memo)
    ->  impure(W),
        Memo = w(LP, K),
        add_weight(W, Acc, LP, K)
    ;   begin_value(W, P0),
        (   weigh_clause(X, T, V, W, Acc, LP, K)
        ->  Memo = w(LP, K),
            (   shared_known(W, X-T) -> true ; store_put(S, X-T, V) )
        ;   Memo = none,
            (   shared_known(W, X-T) -> true ; store_put(S, X-T, '$undef') )
        ),
        (   Acc == evidence -> end_memo(W, P0, Sh, '$w'(X, T), Memo) ; true ),
        impure(W),
        Memo = w(_, _),
        add_weight(W, Acc, LP, K)
    ).

%   end_memo(+W, +P0, +Sh, +K, +Memo): shares Memo (an observation's
%   weight, a sweep's done marker) under key K if computed from shared
%   values only; no world keeps a copy of its own.
end_memo(W, P0, Sh, K, Memo) :-
    world_pure(W, P),
    shared_impure_keys(Sh, Imp),
    (   P == true, shared_enabled(Sh, true), \+ store_get(Imp, K, _)
    ->  shared_store(Sh, SS),
        store_put(SS, K, Memo)
    ;   store_get(Imp, K, _)
    ->  true
    ;   store_put(Imp, K, true)
    ),
    nb_set_world_pure(W, P0).

%   weigh_clause(+X, +T, +V, +W, +Acc, -LogDensity, -Dim): the density of
%   X-T = V under its first applicable clause (Dim: the dimension of V for a
%   density, 0 for a probability mass).
weigh_clause(X, T, V, W, Acc, LP, K) :-
    world_module(W, M),
    world_accumulator(W, Acc0),
    (   Acc0 == Acc -> true ; nb_set_world_accumulator(W, Acc) ),
    (   M:'$rv'(X, T, W, 0, ev(V), Out, Tier, Id, R)
    ->  (   Acc0 == Acc -> true ; nb_set_world_accumulator(W, Acc0) ),
        (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
        (   Out = '$prop'(LJ)
        ->  LP = LJ, K = 0
        ;   Out = '$chk'(D, Id1)
        ->  (   fast_valid(D)
            ->  density(D, V, LP, K)
            ;   cheap_check(D)
            ->  checked(D, Id1, W), density(D, V, LP, K)
            ;   catch(density(D, V, LP, K), E, ( checked(D, Id1, W), throw(E) ))
            )
        ;   density(Out, V, LP, K)
        )
    ;   (   Acc0 == Acc -> true ; nb_set_world_accumulator(W, Acc0) ),
        fail
    ).

density(D, V, LP, K) :-
    dist_log_density(D, V, LP),
    (   dist_discrete(D) -> K = 0 ; value_dim(V, K) ).

add_weight(W, Acc, LP, K) :-
    add_logw(W, Acc, LP),
    (   K == 0 -> true
    ;   Acc == evidence
    ->  world_density_dims(W, DX0), DX is DX0+K, nb_set_world_density_dims(W, DX)
    ;   world_query_density_dims(W, DX0), DX is DX0+K, nb_set_world_query_density_dims(W, DX)
    ).

%   A zero weight (log -inf) does not fail the proof: it marks the world
%   dead, so that "no clause applies" and "weight 0" stay distinct.
add_logw(W, Acc, LP) :-
    (   Acc == evidence -> world_log_weight(W, L0) ; world_query_log_weight(W, L0) ),
    (   LP > -inf, L0 > -inf -> L is L0 + LP
    ;   L is -inf
    ),
    (   Acc == evidence -> nb_set_world_log_weight(W, L) ; nb_set_world_query_log_weight(W, L) ).

value_dim(V, 1) :- number(V), !.
value_dim((_,B), K) :- !, value_dim(B, K0), K is K0+1.
value_dim(L, K) :- is_list(L), !, length(L, K).
value_dim(_, 1).

%   '$read_ev'(X, T, A, W): the evidence value A of X at T, propagated
%   from a val/1 clause.
'$read_ev'(X, T, A, W) :-
    ground(X),
    impure(W),
    world_accumulator(W, Acc),
    (   known(W, X-T, Val)
    ->  Val \== '$undef',
        (   match(Val, A) -> true ; NInf is -inf, add_logw(W, Acc, NInf) )
    ;   weigh_key(X, T, A, W, Acc)
    ).

%   '$read_q'(X, T, V, W): a top-level query literal: ground and not yet
%   sampled, it is weighted instead of sampled.
'$read_q'(X, T, V, W) :-
    (   ground(X), ground(V),
        world_store(W, S), \+ store_get(S, X-T, _), \+ shared_known(W, X-T),
        world_evidence(W, Ev), \+ memberchk((X-T)-_, Ev)
    ->  weigh_key(X, T, V, W, query)
    ;   '$read'(X, T, V, W)
    ).

%   Non-ground random variable: the recorded groundings, and (unless
%   sweeping) those the clause bodies define.
read_enum(X, T, V, W) :-
    impure(W),                          % which keys a world holds is its own
    world_store(W, S),
    findall(X-T, ( store_match(S, X-T, Val), Val \== '$undef' ), Rec0),
    (   world_shared(W, Sh), Sh \== none
    ->  shared_store(Sh, SS),
        findall(X-T, ( store_match(SS, X-T, Val), Val \== '$undef' ), Rec1),
        append(Rec0, Rec1, Rec)
    ;   Rec = Rec0
    ),
    (   world_mode(W, sweep)
    ->  Keys0 = Rec
    ;   world_module(W, M),
        findall(X-T, M:'$rv'(X, T, W, 0, none, _, _, _, _), Def),
        append(Rec, Def, Keys0)
    ),
    sort(Keys0, Keys),
    member(X-T, Keys),
    read_key(X, T, V, W).

'$clause_error'(W, Id, Cause) :-
    world_module(W, M),
    clause_where(M, Id, Where),
    throw(error(ddc(Cause, Where), _)).

clause_where(M, Id, File:Line) :-
    M:'$rv_pos'(Id, File, Line), !.
clause_where(M, _, M:0).

'$fact'(W, G) :-
    world_facts(W, Fs),
    is_list(Fs), Fs \== [],
    functor(G, N, A),
    memberchk(N/A-L, Fs),
    member(G, L).

%   '$undefined'(+World, +Goal): a call to a predicate the program does not
%   define: true for the facts of a filter step that match Goal.
'$undefined'(W, G) :-
    world_facts(W, Fs),
    (   Fs == static
    ->  undefined_in_static(G)
    ;   '$fact'(W, G)
    ).

%!  static_world(!World) is det.
%
%   A world of a static query, which has no facts:
%   a predicate that the program does not define (read from the facts in
%   a filter) is an existence error there, named at the clause that calls
%   it (program_error/4), not a silent failure.
static_world(W) :-
    nb_set_world_facts(W, static).

undefined_in_static(G) :-
    (   G = X:_ -> true ; X = G ),
    functor(X, N, A),
    existence_error(procedure, N/A).

%!  group_facts(+Facts, -Groups) is det.
%
%   Groups: Name/Arity-[Fact, ...]
group_facts(Facts, Groups) :-
    findall(N/A-F, ( member(F, Facts), functor(F, N, A) ), Ps),
    keysort(Ps, Sorted),
    group_pairs_by_key(Sorted, Groups).

'$memo'(W, G, Call) :-
    world_time(W, Now),
    K = '$memo'(G, Now),
    (   known(W, K, V)
    ->  V == true
    ;   world_module(W, M),
        begin_value(W, P0),
        (   call(M:Call) -> V = true ; V = false ),
        (   known(W, K, _) -> impure(W) ; end_value(W, P0, K, V) ),
        V == true
    ).

%   '$shared'(+Key, ?Template, :Goal): the solutions of a clean derived
%   atom (clean_preds/3), computed once per filter step (or filter query)
%   for all particles and kept in a trie keyed by the variant of Key;
%   outside the filter (no shared table) Goal is simply called.
:- meta_predicate '$shared'(+, ?, 0).
'$shared'(Key, Tmpl, Goal) :-
    (   nb_current('$ddc_shared', Tr), Tr \== none
    ->  (   trie_lookup(Tr, Key, L)
        ->  true
        ;   findall(Tmpl, Goal, L),
            ( trie_insert(Tr, Key, L) -> true ; true )
        ),
        member(Tmpl, L)
    ;   call(Goal)
    ).

%   with_shared(:Goal): runs Goal with a fresh table of shared answers.
:- meta_predicate with_shared(0).
with_shared(Goal) :-
    (   nb_current('$ddc_shared', Old) -> true ; Old = none ),
    trie_new(Tr),
    nb_setval('$ddc_shared', Tr),
    call_cleanup(Goal, ( nb_setval('$ddc_shared', Old), trie_destroy(Tr) )).

'$mat'(W, G, T) :-
    functor(G, N, A),
    (   known(W, '$mat'(N/A, T), L)
    ->  true
    ;   world_frozen(W, T),                   % the last frozen time only
        world_module(W, M),
        once(( M:'$sweep'(der, K, N/A, Sw), Sw = sw(_, lazy, _, _, T, W),
               sweep_kind(K, T) )),
        lazy_materialise(W, M, N/A, Sw, T),
        known(W, '$mat'(N/A, T), L)
    ),
    member(G, L).

%   '$range'(+Lo, +Hi, -L): L = [Lo, ..., Hi], as findall(X, between(Lo, Hi,
%   X), L) (whose errors it keeps for non-integers) without its overhead.
'$range'(Lo, Hi, L) :-
    (   integer(Lo), integer(Hi)
    ->  range_(Lo, Hi, L)
    ;   findall(X, between(Lo, Hi, X), L)
    ).

range_(Lo, Hi, L) :-
    (   Lo > Hi
    ->  L = []
    ;   L = [Lo|T], Lo1 is Lo+1, range_(Lo1, Hi, T)
    ).

'$flip'(P) :-
    random_float < P.

'$sample_inline'(D0, X) :-
    (   needs_eval(D0) -> eval_dist(D0, D) ; D = D0 ),
    dist_sample(D, X).

%   '$range_bounds'(+Lo, +Hi, -Lo1, -Hi1): the integer bounds of a range,
%   with between/3's errors.
'$range_bounds'(Lo, Hi, Lo1, Hi1) :-
    Lo1 is Lo, Hi1 is Hi,
    must_be(integer, Lo1),
    must_be(integer, Hi1).

%!  needs_eval(+Dist) is semidet.
%
%   Dist has parameters that are arithmetic expressions.
needs_eval(D) :-
    compound(D),
    compound_name_arguments(D, N, Args),
    (   memberchk(N, [finite, propfinite, logfinite])
    ->  Args = [L], nonvar(L), is_list(L),
        member(P:_, L), compound(P)
    ;   memberchk(N, [val, uniform])
    ->  N == uniform, Args = [A:C], ( compound(A) ; compound(C) )
    ;   member(A, Args), param_needs_eval(A)
    ), !.

param_needs_eval(A) :- var(A), !, fail.
param_needs_eval([H|T]) :- !, ( param_needs_eval(H) ; param_needs_eval(T) ).
param_needs_eval((A,B)) :- !, ( param_needs_eval(A) ; param_needs_eval(B) ).
param_needs_eval(A) :- compound(A).

%!  eval_dist(+D0, -D) is det.
%
%   Evaluates arithmetic expressions in the numeric parameters of D0.
eval_dist(D0, D) :-
    compound(D0), !,
    compound_name_arguments(D0, N, Args0),
    (   memberchk(N, [finite, propfinite, logfinite]), Args0 = [L0], is_list(L0)
    ->  maplist(eval_pair, L0, L), Args = [L]
    ;   N == val
    ->  Args = Args0
    ;   N == uniform, Args0 = [S0]
    ->  (   nonvar(S0), S0 = A0:C0 -> eval_param(A0, A), eval_param(C0, C), Args = [A:C]
        ;   Args = Args0 )
    ;   maplist(eval_param, Args0, Args)
    ),
    compound_name_arguments(D, N, Args).
eval_dist(D, D).

eval_pair(P0:V, P:V) :- !, eval_num(P0, P).
eval_pair(X, X).

eval_param(X, X) :- var(X), !.
eval_param(X, X) :- number(X), !.
eval_param([], []) :- !.
eval_param([H0|T0], [H|T]) :- !, eval_param(H0, H), eval_param(T0, T).
eval_param((A0,B0), (A,B)) :- !, eval_param(A0, A), eval_param(B0, B).
eval_param(X, X) :- atom(X), \+ catch(_ is X, _, fail), !.
eval_param(X, Y) :- eval_num(X, Y).

eval_num(X, X) :- number(X), !.
eval_num(X, Y) :- Y is X.

                 /*******************************
                 *             SWEEP            *
                 *******************************/

%!  sweep(!W, +T) is det.
%
%   Samples every random variable that a transition (or, at
%   T = 0, prior) clause defines at T, and materialise the derived atoms
%   of such clauses.
sweep(W, T) :-
    world_module(W, M),
    nb_set_world_mode(W, sweep),
    (   sweep_plan(W, T, plan(Ids, Ders)) -> true ; sweep_items(M, T, Ids, Ders) ),
    forall(( member(Id, Ids), M:'$sweep'(rv, _, X, Id) ),
           sweep_clause(W, M, Id, X, T)),
    forall(( member(K-NA, Ders), M:'$sweep'(der, K, NA, Sw), Sw = sw(_, eager, _, _, T, W) ),
           materialise(W, M, NA, Sw, T)),
    nb_set_world_mode(W, normal).

%!  sweep_items(+M, +T, -Ids, -Ders) is det.
%
%   What a sweep at T goes through, in
%   order: the transition (or prior) clauses that define random variables
%   (not observations) and the eager derived predicates, as Kind-Name/Arity.
sweep_items(M, T, Ids, Ders) :-
    findall(Id, ( M:'$sweep'(rv, K, X, Id), sweep_kind(K, T), \+ X = observation(_) ), Ids),
    findall(K-N/A, ( M:'$sweep'(der, K, N/A, sw(_, eager, _, _, _, _)), sweep_kind(K, T) ),
            Ders).

%   The sweep plan of a step.  Once the first particle has swept, each
%   transition clause and each eager derived predicate is either shared
%   (its keys found by every particle in the shared store: skipped) or
%   known to be some particle's own (in the impure keys: no particle can
%   share it any more), so which ones the other particles sweep, and in
%   which order, is fixed: plan(ClauseIds, Kind-Name/Arity pairs), kept
%   in the shared store under '$plan'(T) (plan_sweep/3) and followed by
%   every other particle instead of trying every clause (the same calls,
%   in the same order).
sweep_plan(W, T, Plan) :-
    world_shared(W, Sh),
    Sh \== none,
    shared_store(Sh, SS),
    store_get(SS, '$plan'(T), Plan).

%!  plan_sweep(+M, +Sh, +T) is det.
%
%   Records the plan of step T, after the first
%   particle's sweep.
plan_sweep(M, Sh, T) :-
    shared_store(Sh, SS),
    sweep_items(M, T, Ids0, Ders0),
    exclude(swept_shared(SS, T), Ids0, Ids),
    exclude(materialised_shared(SS, T), Ders0, Ders),
    store_put(SS, '$plan'(T), plan(Ids, Ders)).

swept_shared(SS, T, Id) :-
    store_get(SS, '$swept'(Id, T), _).

materialised_shared(SS, T, _-NA) :-
    store_get(SS, '$mat'(NA, T), _).

%   sweep_clause(+W, +M, +Id, ?X, +T): samples the keys X-T that clause Id
%   defines.  If none of them needed anything of a particle's own (all
%   shared, see "Shared values" above), that holds in every particle:
%   marked '$swept'(Id, T) in the shared store, the clause is skipped in
%   the particles that come after.
sweep_clause(W, _, Id, _, T) :-
    shared_known(W, '$swept'(Id, T)),
    !.
sweep_clause(W, M, Id, X, T) :-
    begin_value(W, P0),
    forall(sweep_candidate(M, Id, X, T, W),
           (   ground(X) -> ignore('$read'(X, T, _, W))
           ;   '$clause_error'(W, Id, non_ground_head(X))
           )),
    world_shared(W, Sh),                     % (a particle sweeps only in a step)
    end_memo(W, P0, Sh, '$swept'(Id, T), done).

%   materialise(+W, +M, +N/A, +Sw, +T): the instances of derived
%   predicate N/A at T, from its transition clauses, recorded as
%   '$mat'(N/A, T) (time T is then frozen: no longer derivable).
materialise(W, _, N/A, _, T) :-
    known(W, '$mat'(N/A, T), _),
    !.
materialise(W, M, N/A, sw(Sh, _, G, H1, T, W), T) :-
    begin_value(W, P0),
    (   Sh == shared
    ->  findall(G, ( '$shared'('$sweep'(G):T, G, M:H1), ground(G) ), L0)
    ;   findall(G, ( M:H1, ground(G) ), L0)
    ),
    sort(L0, L),
    K = '$mat'(N/A, T),
    (   known(W, K, _) -> impure(W) ; end_value(W, P0, K, L) ).

%   A derived predicate the program never reads one step back (only at
%   t+1) is not materialised by the sweep: the first read at the last
%   frozen time T (a query after the step) materialises it, in the state
%   the sweep would have seen (T derivable again, sweep mode) before
%   freezing T again.  Once the next step has begun, such an atom at
%   T-1 or earlier can no longer be derived (its inputs are pruned).
lazy_materialise(W, M, NA, Sw, T) :-
    world_frozen(W, Frozen),
    world_mode(W, Mode),
    Frozen1 is T-1,
    setup_call_cleanup(( nb_set_world_frozen(W, Frozen1), nb_set_world_mode(W, sweep) ),
                       materialise(W, M, NA, Sw, T),
                       ( nb_set_world_frozen(W, Frozen), nb_set_world_mode(W, Mode) )).

%   (Sharing the candidates of clauses whose key prefix is clean, as the
%   derived atoms are, was measured slower: those prefixes are one or two
%   fact lookups, cheaper than the shared table's findall and copy.)
sweep_candidate(M, Id, X, T, W) :-
    M:'$sweep_key'(Id, X, T, W).

%!  sweep_kind(+Kind, +T) is semidet.
%
%   A clause of Kind defines values at T (a sweep at T goes through it).
sweep_kind(trans, T) :- T >= 1.
sweep_kind(persist, T) :- T >= 1.
sweep_kind(fixed(T), T).
