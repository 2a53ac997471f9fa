/** <module> The per-particle engine of the DDC filter

Part of the DDC engine (ddc.pl is the module users load).  Steps, queries
and resamples the particles of a filter one particle at a time, each a
world of the runtime (ddc_world.pl) proved by the program's compiled
clauses.  Implements the engine interface of the filter API
(ddc_filter.pl, "Engines"); the batched engine is ddc_batch.pl.

A step t -> t+1 for each particle:
  1. the facts of t+1 (actions, plain observations such as
     observed(b1)) replace those of t;
  2. every observation h ~= v is recorded, once for all particles, as
     h:t+1 and as the untimed h (the original's bodies read
     observation(x) ~= V untimed; an untimed h that already has a value
     keeps it); then each observation weights the particle once, by
     the density of h's first applicable clause at t+1 (h:t+1 clauses,
     else h:t clauses, else untimed ones), whose proof sees every
     observation's value and samples lazily whatever transitions it
     needs (the original weighted an observation when a proof first
     read it, and recorded it after);
  3. the transition clauses (h:t+1 heads) are swept: every ground head
     their bodies produce (non-ground reads in those bodies see only
     the values recorded) is sampled, every derived h:t+1 atom is
     materialised; heads observation(_) are left out (as in the
     original: observations are not predicted, only weighted);
  4. time t is no longer derivable (frozen): queries at t+1 may still
     read h:t; the values of t-1 and the raw observations of t are
     dropped at the start of the next step.
Values the particles agree on are computed once (see "Shared values"
in ddc_world.pl).  Step and resample keep the previous particles for
one undo.  A step either completes for all particles or changes
nothing.

Threads (filter_new/5 option threads(K)): the first particle is stepped
alone (it finds the values every particle shares, and a step in which
nothing else is left is settled at once); the others are split into K
contiguous groups, the first stepped by the calling thread, each other
one by a worker thread (ddc_pool.pl) on a copy of its particles and of
the shared values, drawing from a random stream seeded (after the
first particle) from the filter's.  The copies come back into the
filter's particles and their newly shared values join its own
(step_groups/10).  K is part of the seed: the same K gives the same
particles on any machine.
*/

:- module(ddc_particles,
          [ particles_new/7,            % +Name, +Module, +N, +Seed, +Share, +Threads, -State
            merge_shared/4,             % +Shared, +GroupShared, !Worlds, +Lo-Len
            group_agreement/6,          % +Worlds, +Lo, +Hi, +Shared, +T, -Agreed
            stored_values/8,            % +I, +N, +Worlds, +SharedStore, +Key, +V, +Tmpl, -Values
            stored_rows/7               % +I, +N, +Worlds, +SharedStore, +Key, +Width, -Floats
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(aggregate)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module('../lang/ddc_records').
:- use_module('../runtime/ddc_store').
:- use_module('../lang/ddc_body').
:- use_module('../runtime/ddc_world').
:- use_module('../lang/ddc_programs', [optimised/1]).
:- use_module('../runtime/ddc_pool').
:- use_module('../runtime/ddc_rows').
:- use_module('../runtime/ddc_rename', [rename_term/3, rename_arguments/3]).

:- use_module('../lang/ddc_ops').

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%   A per-particle filter's state, held by the filter (ddc_filter.pl) and
%   updated in place: its name (the filter's, which names its global
%   variables), its program's module, the number of particles, the time,
%   the particles (a term ws(W1, ..., WN) of worlds), the previous state
%   for one undo (none, or a record previous(Time, Worlds, Shared)), the
%   state of its random generator and its shared values (ddc_world.pl,
%   record shared).
:- record_type particles(name, module, size, time, worlds, previous, rng, shared).
:- record_type previous(time, worlds, shared).

                 /*******************************
                 *       ENGINE INTERFACE       *
                 *******************************/

%!  particles_new(+Name, +Module, +N, +Seed, +Share, +Threads, -State) is det.
%
%   The state of a new filter of N particles at time 0 of the program in
%   Module: every h:0 clause whose body holds is sampled (and h:0 derived
%   atoms materialised); h:t clauses stay lazy.
particles_new(F, M, N, Seed, Share, K, State) :-
    set_random(seed(Seed)),
    length(L, N),
    new_shared(Share, K, Sh0),
    atom_concat(F, '$new', FN),
    nb_setval(FN, Sh0),
    nb_getval(FN, Sh),                  % global: survives the query, changed in place
    with_shared(maplist(init_particle(M, Sh), L)),
    nb_delete(FN),
    Ws =.. [ws|L],
    random_property(state(R)),
    State = particles(F, M, N, 0, Ws, none, R, Sh).

%   A particle's own store is not indexed (particle_store/1).
init_particle(M, Sh, W) :-
    new_world(M, 0, -1, [], W),
    particle_store(S),
    nb_set_world_store(W, S),
    nb_link_world_shared(W, Sh),
    sweep(W, 0),
    nb_set_world_shared(W, none),
    nb_set_world_pure(W, false),
    nb_set_world_frozen(W, 0).

%   particle_store(-S): a particle's own store.  It holds what a particle
%   has of its own, few keys even when the shared store holds many: a
%   non-ground read scans it as fast as an index would find its keys, and
%   the index would cost an entry per insertion and make every particle
%   larger to copy (measured: a hidden-ball step of too.pl at N = 1000,
%   one thread, 118.5 -> 110.8 ms; bench/filter_step.py 194 -> 174 ms).
particle_store(S) :-
    store_new(S, false).


%   engine_step(!State, +Weighted, +Facts, -LogWeights)
engine_step(State, Weighted, Facts0, LogWs) :-
    particles_module(State, M),
    particles_size(State, N),
    particles_time(State, T),
    particles_worlds(State, Ws0),
    particles_rng(State, R0),
    particles_shared(State, Sh0),
    T1 is T+1,
    M:'$ddc_info'(Info),
    group_facts(Facts0, Facts),
    maplist(observation_key(Info, T1), Weighted, Keys),
    particles_name(State, F),
    scratch_copy(F, Ws0, Sh0, Ws, Sh),
    record_observations(Sh, T, Keys),
    with_random_stream(state(R0),
                       with_shared(step_particles(Ws, N, M, T1, Keys, Facts, Sh, LogWs,
                                                  Agreed)),
                       R1),
    share_agreed(Ws, N, Sh, T1, Agreed),
    commit(State, T1, Ws, Sh, T, Ws0, Sh0, R1).

%   engine_undo(!State): the particles, shared values and time from before
%   the last step (or resampling); only one level is kept.  Fails if there
%   is none (the filter API raises the error).
engine_undo(State) :-
    particles_previous(State, Prev),
    (   Prev \== none
    ->  previous_time(Prev, T0),
        previous_worlds(Prev, Ws0),
        previous_shared(Prev, Sh0),
        nb_set_particles_time(State, T0),
        nb_link_particles_worlds(State, Ws0),
        nb_link_particles_shared(State, Sh0),
        nb_set_particles_previous(State, none)
    ).

%   engine_resample(!State, +Indices): particle i (1-based position in
%   Indices) becomes a copy of particle Indices[i] (0-based).
engine_resample(State, Is) :-
    particles_time(State, T),
    particles_worlds(State, Ws0),
    particles_rng(State, R),
    particles_shared(State, Sh),
    %   findall/3 copies each chosen particle on its own: copies of one
    %   particle are independent worlds; the new set is linked, not copied
    %   again (it holds no variable bound outside it)
    findall(W, ( member(I, Is), I1 is I+1, arg(I1, Ws0, W) ), L),
    Ws =.. [ws|L],
    commit(State, T, Ws, Sh, T, Ws0, Sh, R).

%   engine_rename(!State, +Moves, +Is): in the particles Is (1-based,
%   sorted), the constants renamed by Moves (filter_rename/3): each one's
%   store is built anew with its entries renamed (renamed_entry/3).  A
%   shared value that the rename changes (its key or its value names a
%   moved constant) cannot stay shared: it leaves a copy of the shared
%   values (the previous state, kept for undo, may hold the same record),
%   goes into every particle's own store (renamed in the renamed ones) and
%   into the impure keys, so that nothing computed from it later is
%   shared; so do the keys the renamed particles now hold.  A moved key
%   that leaves the shared store leaves the step's moved list too (its
%   copies are no longer dropped at the next step).  The untimed copies
%   of the step's observations (raw keys) are the step's input: they stay.
%   The particles are the filter's own terms (a step and a resampling
%   make new ones; the previous state keeps its own): changed in place.
engine_rename(State, Moves, Is) :-
    particles_name(State, F),
    particles_size(State, N),
    particles_time(State, T),
    particles_worlds(State, Ws),
    particles_shared(State, Sh0),
    atom_concat(F, '$rename', FN),
    nb_setval(FN, Sh0),
    nb_getval(FN, Sh),
    shared_store(Sh, SS), shared_impure_keys(Sh, Impure), shared_raw_keys(Sh, Raw),
    findall(KV, ( store_match(SS, K, V), value_key(K), \+ memberchk(K, Raw),
                  KV = K-V, renamed_entry(Moves, KV, KV1), KV1 \== KV ),
            Unshared),
    forall(member(K-_, Unshared), ( store_delete(SS, K), impure_key(Impure, K) )),
    drop_moved(SS, T, Unshared),
    (   Unshared == []
    ->  Others = []
    ;   numlist(1, N, All), ord_subtract(All, Is, Others)
    ),
    forall(member(I, Others),
           forall(member(K-V, Unshared), own_copy(Ws, I, K, V))),
    forall(( member(I, Is), arg(I, Ws, W) ),
           rename_world(W, Moves, Unshared, Impure)),
    nb_link_particles_shared(State, Sh),
    nb_delete(FN).

%   value_key(+Key): a key of a value a particle holds (a random variable
%   X-T, a memoised or materialised derived atom), not a step's marker.
value_key(_-_).
value_key('$memo'(_, _)).
value_key('$mat'(_, _)).

%   renamed_entry(+Moves, +K-V, -K1-V1): a store entry renamed: a random
%   variable's arguments and its value, a memoised atom's arguments (its
%   value is true or false; a timed one is A:T), the arguments of each instance of a
%   materialised predicate.
renamed_entry(Moves, (X-T)-V, (X1-T)-V1) :- !,
    rename_arguments(Moves, X, X1),
    rename_term(Moves, V, V1).
renamed_entry(Moves, '$memo'(G, T)-V, '$memo'(G1, T)-V) :- !,
    (   G = A:TA                        % a timed derived atom A:TA
    ->  rename_arguments(Moves, A, A1),
        G1 = A1:TA
    ;   rename_arguments(Moves, G, G1)
    ).
renamed_entry(Moves, '$mat'(NA, T)-L, '$mat'(NA, T)-L1) :-
    maplist(rename_arguments(Moves), L, L1).

impure_key(Impure, K) :-
    (   store_get(Impure, K, _) -> true ; store_put(Impure, K, true) ).

%   drop_moved(!SS, +T, +Unshared): the keys of Unshared are no longer in
%   the list of keys of time T that moved to the shared store
%   (moved_keys/3).
drop_moved(SS, T, Unshared) :-
    (   Unshared \== [],
        store_get(SS, '$moved'(T), Keys0),
        exclude(unshared_key(Unshared), Keys0, Keys),
        Keys \== Keys0
    ->  store_delete(SS, '$moved'(T)),
        store_put(SS, '$moved'(T), Keys)
    ;   true
    ).

unshared_key(Unshared, K) :-
    memberchk(K-_, Unshared).

%   rename_world(!W, +Moves, +Unshared, !Impure): W's store anew: its own
%   entries and those of Unshared it does not hold, renamed.
rename_world(W, Moves, Unshared, Impure) :-
    world_store(W, S0),
    store_entries(S0, Own),
    exclude(held_in(S0), Unshared, FromShared),
    particle_store(S1),
    nb_set_world_store(W, S1),
    world_store(W, S),
    forall(( member(KV, Own) ; member(KV, FromShared) ),
           (   renamed_entry(Moves, KV, K1-V1),
               store_put(S, K1, V1),
               impure_key(Impure, K1)
           )).

held_in(S, K-_) :-
    store_get(S, K, _).

engine_holds(State, Goal, Flags) :-
    particles_query(State, Goal, true, Sols),
    maplist(solution_flag, Sols, Flags).

solution_flag(S, B) :-
    (   S == none -> B = 0 ; B = 1 ).

engine_values(State, Template, Goal, Values) :-
    particles_query(State, Goal, Template, Values).

%   engine_rows(+State, +Template, +Goal, -Width, -Floats) is semidet: a
%   goal `h ~= V` with template V and ground h (a random variable's
%   values) is read straight from the particles' stores, without building
%   the values, when every particle holds one.
engine_rows(State, Template, Goal, Width, Floats) :-
    particles_module(State, M),
    particles_size(State, N),
    particles_time(State, T),
    particles_worlds(State, Ws),
    particles_shared(State, Sh),
    M:'$ddc_info'(Info),
    stored_read(Goal, Template, ctx(_, T, Info, query), Key, V, Tmpl),
    Tmpl == V,
    shared_store_or_none(Sh, SS),
    first_row_width(1, N, Ws, SS, Key, Width0),
    stored_rows(1, N, Ws, SS, Key, Width0, Floats0),
    !,
    Width = Width0, Floats = Floats0.

engine_time(State, T) :-
    particles_time(State, T).

engine_size(State, N) :-
    particles_size(State, N).

%   Stats: [particles(N), time(T), shared(S), own(O), settled_steps(K)]
engine_statistics(State, [particles(N), time(T), shared(S), own(O), settled_steps(K)]) :-
    particles_size(State, N),
    particles_time(State, T),
    particles_worlds(State, Ws),
    particles_shared(State, Sh),
    shared_store(Sh, Shared),
    shared_settled_steps(Sh, K),
    store_size(Shared, S),
    aggregate_all(sum(C), ( between(1, N, I), arg(I, Ws, W), world_store(W, St), store_size(St, C) ), O).

engine_free(_).

                 /*******************************
                 *            STEPS             *
                 *******************************/

%   share_agreed(+Ws, +N, +Sh, +T, +Agreed): a value of time T that every
%   particle computed from its own values but that came out the same in all
%   of them (an object seen again is where it was seen, whatever each
%   particle had believed; a variable undefined in every particle) moves to
%   the shared store, so that what is computed from it next can be shared
%   again.  Agreed: for each group of particles 2..N, the keys of time T
%   its particles agree on, with their value (group_agreement/6, found by
%   the thread that stepped the group), or none (then checked here).  The
%   particles' own copies (the same value) are dropped when each particle
%   next steps (moved_keys/3), by the thread that steps it; until then a
%   query finds the same value in either place.
share_agreed(Ws, N, Sh, T, Agreed) :-
    shared_enabled(Sh, true),
    !,
    shared_store(Sh, Shared),
    shared_impure_keys(Sh, Impure),
    findall(K, ( store_match(Impure, K, _), own_key_at(K, T) ), Ks),
    arg(1, Ws, W1),
    world_store(W1, S1),
    findall(K-V, ( member(K, Ks), store_get(S1, K, V),
                   (   Agreed == none
                   ->  agreed(2, N, Ws, K, V)
                   ;   forall(member(GA, Agreed), group_agrees(GA, K, V))
                   ) ),
            Moved),
    forall(member(K-V, Moved),
           (   store_put(Shared, K, V),
               store_delete(Impure, K)
           )),
    (   Moved == []
    ->  true
    ;   pairs_keys(Moved, MovedKeys),
        store_put(Shared, '$moved'(T), MovedKeys)
    ).
share_agreed(_, _, _, _, _).

group_agrees(any, _, _).
group_agrees(agreed(KVs), K, V) :-
    memberchk(K-V1, KVs),
    V1 == V.

%   group_agreement(+Ws, +Lo, +Hi, +Sh, +T, -Agreed): the keys of time T
%   that particles Lo..Hi of Ws hold as their own, each with the same value
%   in all of them, as agreed([K-V, ...]) (any for no particles, agreed([])
%   when nothing is shared).
group_agreement(Ws, Lo, Hi, Sh, T, Agreed) :-
    (   Lo > Hi
    ->  Agreed = any
    ;   shared_enabled(Sh, true)
    ->  shared_impure_keys(Sh, Impure),
        arg(Lo, Ws, W),
        world_store(W, S),
        Lo1 is Lo+1,
        findall(K-V, ( store_match(Impure, K, _), own_key_at(K, T),
                       store_get(S, K, V), agreed(Lo1, Hi, Ws, K, V) ),
                KVs),
        Agreed = agreed(KVs)
    ;   Agreed = agreed([])
    ).

%   moved_keys(+Sh, +T, -Keys): the keys of time T that moved to the shared
%   store after the step to T (share_agreed/5).
moved_keys(Sh, T, Keys) :-
    shared_store(Sh, Shared),
    (   store_get(Shared, '$moved'(T), Keys0) -> Keys = Keys0 ; Keys = [] ).

own_key_at(_-T, T).
own_key_at('$mat'(_, T), T).
own_key_at('$memo'(_, T), T).

agreed(I, N, Ws, K, V) :-
    (   I > N
    ->  true
    ;   arg(I, Ws, W),
        world_store(W, S),
        store_get(S, K, V1),
        V1 == V,
        I1 is I+1,
        agreed(I1, N, Ws, K, V)
    ).

%   step_particles(+Ws, +N, +M, +T1, +Keys, +Facts, +Sh, -LogWs, -Agreed): steps
%   every particle.  If the first particle's step left nothing of its own
%   (every observation's weight, every transition clause and every derived
%   atom of t+1 shared), every other particle's step would only find the
%   same shared values: each gets the first one's weight and is only moved
%   to t+1 (a frame in which the particles agree costs next to nothing).
%   Else the others are stepped in groups (step_groups/10).  Agreed: see
%   share_agreed/5.
step_particles(Ws, N, M, T1, Keys, Facts, Sh, [LW1|LWs], Agreed) :-
    own_particle(Ws, 1, W1),
    nb_set_world_check_overlaps(W1, true),
    step_particle(W1, T1, Keys, Facts, Sh, LW1),
    shared_threads(Sh, K),
    group_seeds(K, Seeds),              % drawn in any case: the draws after
    (   settled(M, Sh, T1, Keys)        % do not depend on settling
    ->  shared_settled_steps(Sh, S0),
        S is S0+1,
        nb_set_shared_settled_steps(Sh, S),
        world_density_dims(W1, DX),
        T is T1-1,
        moved_keys(Sh, T, Moved),
        findall(LW1, ( between(2, N, I), own_particle(Ws, I, W),
                       settled_step(W, T1, Facts, LW1, DX, Moved) ), LWs),
        Agreed = none
    ;   plan_sweep(M, Sh, T1),
        groups_seeds(Seeds, N, GroupSeeds),
        step_groups(GroupSeeds, Ws, N, M, T1, Keys, Facts, Sh, LWs, Agreed)
    ).

%   groups_seeds(+Seeds, +N, -GroupSeeds): the seeds of the groups that
%   are not empty: particles 2..N make at most N-1 groups (each group but
%   the first has a seed of its own).
groups_seeds(Seeds, N, GroupSeeds) :-
    length(Seeds, K1),
    Used is max(0, min(K1, N-2)),
    length(GroupSeeds, Used),
    append(GroupSeeds, _, Seeds).


%   step_groups(+Seeds, +Ws, +N, +M, +T1, +Keys, +Facts, +Sh, -LogWs,
%   -Agreed): particles 2..N in 1 + length(Seeds) contiguous groups.  The first
%   group is stepped here, each other one by a worker thread on a copy of
%   its particles and of the shared values, from its seed; then their
%   particles replace the copies' originals and their shared values join
%   this thread's (merge_shared/4).  An error in any group is raised here
%   after every group has been stepped; the step then changes nothing.
step_groups([], Ws, N, M, T1, Keys, Facts, Sh, LWs, [Agreed]) :-
    !,
    step_range(2, N, Ws, M, T1, Keys, Facts, Sh, LWs),
    group_agreement(Ws, 2, N, Sh, T1, Agreed).
step_groups(Seeds, Ws, N, M, T1, Keys, Facts, Sh, LWs, [Agreed0|GAgreed]) :-
    length(Seeds, K1),
    K is K1+1,
    group_bounds(2, N, K, [Lo-Hi|Others]),
    maplist(group_job(Ws, T1, Keys, Facts, Sh), Seeds, Others, Jobs),
    pool_run(( step_range(Lo, Hi, Ws, M, T1, Keys, Facts, Sh, LWs0),
               group_agreement(Ws, Lo, Hi, Sh, T1, Agreed0) ),
             Jobs, Results),
    maplist(join_particles(Ws), Others, Results, GLWss),
    maplist(join_shared(Ws, Sh), Others, Results),
    maplist(result_agreement, Results, GAgreed),
    append([LWs0|GLWss], LWs).

result_agreement(done(_, _, _, Agreed), Agreed).


%   group_job(+Ws, ..., +Seed, +Lo-Hi, -Job): the job (ddc_pool.pl's
%   pool_run/3) that steps the particles Lo..Hi of Ws, copied into a vector
%   of their own, from random seed Seed.
group_job(Ws, T1, Keys, Facts, Sh, Seed, Lo-Hi, Job) :-
    sub_vector(Lo, Hi, Ws, L),
    GWs =.. [ws|L],
    Job = step_group(Seed, Lo, GWs, T1, Keys, Facts, Sh, Out)-Out.

%   step_group(+Seed, +Lo, !GWs, ..., -Out): a worker's job, the particles
%   GWs (Lo..: their places in the filter) stepped from random seed Seed;
%   Out = done(GWs, Sh, LogWeights, Agreed).
step_group(Seed, Lo, GWs, T1, Keys, Facts, Sh, done(GWs, Sh, LWs, Agreed)) :-
    functor(GWs, _, Len),
    set_random(seed(Seed)),
    with_shared(step_range_at(1, Len, Lo, held, GWs, T1, Keys, Facts, Sh, LWs)),
    group_agreement(GWs, 1, Len, Sh, T1, Agreed).

sub_vector(I, Hi, Ws, L) :-
    (   I > Hi
    ->  L = []
    ;   arg(I, Ws, W),
        L = [W|L1],
        I1 is I+1,
        sub_vector(I1, Hi, Ws, L1)
    ).

%   The particles a worker stepped replace their originals in Ws (all
%   groups first: joining shared values may add to any group's particles).
join_particles(Ws, Lo-_, done(GWs, _, GLWs, _), GLWs) :-
    functor(GWs, _, Len),
    forall(between(1, Len, J),
           ( I is Lo+J-1, arg(J, GWs, W), nb_linkarg(I, Ws, W) )).

join_shared(Ws, Sh, Lo-_, done(GWs, GSh, _, _)) :-
    functor(GWs, _, Len),
    merge_shared(Sh, GSh, Ws, Lo-Len).

%   merge_shared(+Sh, +GSh, +Ws, +Lo-Len): the values a group computed
%   once for its particles join Sh, and the keys it holds per particle
%   join Sh's impure keys.  A value one side shared and the other computed
%   per particle (possible only when the particles' own values differed in
%   which keys they hold) goes, on the sharing side, into every particle's
%   own store, and stays out of the shared store.
merge_shared(Sh, GSh, Ws, Lo-Len) :-
    shared_store(Sh, Shared), shared_impure_keys(Sh, Impure),
    shared_store(GSh, GShared), shared_impure_keys(GSh, GImpure),
    Hi is Lo+Len-1,
    forall(( store_match(GShared, K, V), \+ store_get(Shared, K, _) ),
           (   store_get(Impure, K, _)
           ->  own_copies(Ws, Lo, Hi, K, V)
           ;   store_put(Shared, K, V)
           )),
    forall(( store_match(GImpure, K, _), \+ store_get(Impure, K, _) ),
           (   store_get(Shared, K, V)
           ->  store_delete(Shared, K),
               functor(Ws, _, N),
               forall(( between(1, N, I), ( I < Lo ; I > Hi ) ), own_copy(Ws, I, K, V)),
               store_put(Impure, K, true)
           ;   store_put(Impure, K, true)
           )).

own_copies(Ws, Lo, Hi, K, V) :-
    forall(between(Lo, Hi, I), own_copy(Ws, I, K, V)).

own_copy(Ws, I, K, V) :-
    arg(I, Ws, W),
    world_store(W, S),
    (   store_get(S, K, _) -> true ; store_put(S, K, V) ).

%   step_range(+Lo, +Hi, +Ws, ...): steps particles Lo..Hi of the step's
%   scratch vector Ws (each copied from the filter's before it changes);
%   the first overlap_checked_particles/1 particles of the filter check for
%   overlapping clauses.
step_range(Lo, Hi, Ws, _, T1, Keys, Facts, Sh, LWs) :-
    step_range_at(Lo, Hi, 1, own, Ws, T1, Keys, Facts, Sh, LWs).

%   (First: the filter's index of Ws's particle 1; Copy: own to copy each
%   particle first, held if Ws holds copies already.)
step_range_at(Lo, Hi, First, Copy, Ws, T1, Keys, Facts, Sh, LWs) :-
    overlap_checked_particles(Checked),
    findall(LW, ( between(Lo, Hi, I),
                  ( Copy == own -> own_particle(Ws, I, W) ; arg(I, Ws, W) ),
                  ( I+First-1 =< Checked -> Check = true ; Check = false ),
                  nb_set_world_check_overlaps(W, Check),
                  step_particle(W, T1, Keys, Facts, Sh, LW) ), LWs).

settled(M, Sh, T1, Keys) :-
    shared_enabled(Sh, true),
    shared_store(Sh, Shared),
    forall(member(k(X, T, _, _), Keys),
           store_get(Shared, '$w'(X, T), w(_, _))),
    forall(( M:'$sweep'(rv, K, X, Id), sweep_kind(K, T1), \+ X = observation(_) ),
           store_get(Shared, '$swept'(Id, T1), _)),
    forall(( M:'$sweep'(der, K, N/A, Sw), Sw = sw(_, eager, _, _, T1, _), sweep_kind(K, T1) ),
           store_get(Shared, '$mat'(N/A, T1), _)).

%   What step_particle/6 would do to a particle once settled/4 holds.
settled_step(W, T1, Facts, LW, DX, Moved) :-
    world_store(W, S),
    T is T1-1,
    store_prune(S, T, Moved),
    nb_set_world_time(W, T1),
    nb_link_world_facts(W, Facts),
    nb_set_world_log_weight(W, LW),
    nb_set_world_density_dims(W, DX),
    nb_set_world_frozen(W, T1).

%   record_observations(+Sh, +T, +Keys): drops the values of times before T
%   and the previous step's observations from the shared store and records
%   this step's: an observation's value is the same in every particle.  A
%   timed observation is also recorded untimed, for bodies that read it
%   raw (the original's bodies read observation(x) ~= V untimed), unless
%   the untimed variable has a value already; both go at the next step.
record_observations(Sh, T, Keys) :-
    shared_store(Sh, Shared), shared_impure_keys(Sh, Impure), shared_raw_keys(Sh, Raw0),
    store_prune(Shared, T, Raw0),
    store_prune(Impure, T, []),
    foldl(record_observation(Shared), Keys, [], Raw),
    nb_set_shared_raw_keys(Sh, Raw).

record_observation(Shared, k(X, T, V, _), Raw0, Raw) :-
    (   store_get(Shared, X-T, _)
    ->  Raw1 = Raw0
    ;   store_put(Shared, X-T, V),
        ( T == u -> Raw1 = [X-u|Raw0] ; Raw1 = Raw0 )
    ),
    (   T == u -> Raw = Raw1
    ;   store_get(Shared, X-u, _) -> Raw = Raw1
    ;   store_put(Shared, X-u, V),
        Raw = [X-u|Raw1]
    ).

%   scratch_copy(+F, +Ws0, +Sh0, -Ws, -Sh): Sh is a copy of Sh0 and Ws a
%   vector of Ws0's particles, both held by a global variable (so that
%   they survive the query and can be changed in place).  Ws's arguments
%   are Ws0's particles themselves, not copies: a particle is copied when
%   this thread first changes it (own_particle/3), and one that a worker
%   steps is copied by the message that takes it there, so none is copied
%   twice and Ws0 stays as it was (for filter_undo/1, and for an error in
%   the middle of the step).
scratch_copy(F, Ws0, Sh0, Ws, Sh) :-
    atom_concat(F, '$next', FN),
    functor(Ws0, Name, N),
    functor(Ws1, Name, N),
    nb_setval(FN, Ws1-Sh0),
    nb_getval(FN, Ws-Sh),
    forall(between(1, N, I), ( arg(I, Ws0, W0), nb_linkarg(I, Ws, W0) )).

%   own_particle(+Ws, +I, -W): particle I of the scratch vector, first
%   copied from the filter's (called once per particle and step, before
%   this thread changes it).
own_particle(Ws, I, W) :-
    arg(I, Ws, W0),
    nb_setarg(I, Ws, W0),
    arg(I, Ws, W).

%   commit: the filter now holds Ws and the shared values Sh at time T and
%   keeps Ws0, Sh0 (time T0) for filter_undo/1.  All are global terms
%   already, so they are linked, not copied again.
commit(State, T, Ws, Sh, T0, Ws0, Sh0, R) :-
    nb_set_particles_previous(State, previous(T0, '$', '$')),
    particles_previous(State, Prev),
    nb_link_previous_worlds(Prev, Ws0),
    nb_link_previous_shared(Prev, Sh0),
    nb_link_particles_worlds(State, Ws),
    nb_link_particles_shared(State, Sh),
    nb_set_particles_time(State, T),
    nb_set_particles_rng(State, R),
    particles_name(State, F),
    atom_concat(F, '$next', FN),
    nb_delete(FN).


%   observation_key(+Info, +T1, +Obs, -k(X, T, V, Obs))
observation_key(Info, T1, (H ~= V), k(X, T, V, (H ~= V))) :-
    read_key_code(H, ctx(_, T1, Info, query), X, T, TG),
    call(TG).

step_particle(W, T1, Keys, Facts, Sh, LW) :-
    %   everything before time t (kept until now for queries at t that look
    %   one step back) goes, and so do the values of t now shared
    world_store(W, S),
    T is T1-1,
    moved_keys(Sh, T, Moved),
    store_prune(S, T, Moved),
    nb_set_world_time(W, T1),
    nb_link_world_facts(W, Facts),           % ground, shared by all particles: no copy
    nb_link_world_shared(W, Sh),              % (unlinked at the end: copies of W never copy Sh)
    nb_set_world_log_weight(W, 0.0),
    nb_set_world_density_dims(W, 0),
    weigh_observations(Keys, W),
    world_log_weight(W, LW),
    sweep(W, T1),
    nb_set_world_frozen(W, T1),
    nb_set_world_shared(W, none),
    nb_set_world_pure(W, false),
    !.

%   Each observation weights the particle once, by the density of its
%   first applicable clause (whose proof sees every observation's value).
weigh_observations([], _).
weigh_observations([k(X, T, V, O)|Ks], W) :-
    (   weigh_key(X, T, V, W, evidence)
    ->  weigh_observations(Ks, W)
    ;   throw(error(ddc(no_observation_clause(O), query), _))
    ).

                 /*******************************
                 *            QUERIES           *
                 *******************************/

filter_literal(Ctx, G, C) :-
    compile_body(G, Ctx, C).

particles_query(State, Goal, Template, Values) :-
    particles_module(State, M),
    particles_size(State, N),
    particles_time(State, T),
    particles_worlds(State, Ws),
    particles_rng(State, R0),
    particles_shared(State, Sh),
    M:'$ddc_info'(Info),
    (   stored_read(Goal, Template, ctx(_, T, Info, query), Key, V, Tmpl),
        shared_store_or_none(Sh, SS),
        stored_values(1, N, Ws, SS, Key, V, Tmpl, Values)
    ->  true
    ;   proved_values(State, M, N, T, Ws, R0, Sh, Info, Goal, Template, Values)
    ).

%   stored_read(+Goal, +Template, +Ctx, -Key, -V, -Tmpl): Goal is a single
%   read `h ~= V` of a ground random variable with V unbound (the common
%   "where is it in each particle" query): each particle that holds a value
%   of Key answers from its store (its own value first, then the shared
%   one), exactly as read_key/4 would, without compiling and proving the
%   goal.  (Tmpl-V: a copy of Template-V.)
stored_read(Goal, Template, Ctx, X-T, V, Tmpl) :-
    copy_term(Goal-Template, G1-Tmpl),
    nonvar(G1), G1 = (H ~= V), var(V),
    catch(read_key_code(H, Ctx, X, T, TG), _, fail),
    ground(X), call(TG), integer(T).

%   stored_values(+I, +N, +Ws, +SS, +Key, +V, +Tmpl, -Values): fails if a
%   particle holds no value of Key (it would be sampled or weighed: the
%   goal is then proved as any other).
stored_values(I, N, Ws, SS, Key, V, Tmpl, Values) :-
    (   I > N
    ->  Values = []
    ;   stored_value(I, Ws, SS, Key, Val),
        (   Val == '$undef'
        ->  Value = none
        ;   copy_term(V-Tmpl, Val-Value)
        ),
        Values = [Value|Values1],
        I1 is I+1,
        stored_values(I1, N, Ws, SS, Key, V, Tmpl, Values1)
    ).

proved_values(State, M, N, T, Ws, R0, Sh, Info, Goal, Template, Values) :-
    flag(ddc_query_id, Id, Id+1),
    copy_term(Goal-Template, G1-X1),
    Ctx = ctx(W, T, Info, query),
    conj_list(G1, Ls),
    maplist(filter_literal(Ctx), Ls, Cs),
    conj_from_list(Cs, Code),
    optimised(assertz(M:('$ddc_tmp'(Id, q, W, X1) :- Code))),
    call_cleanup(
        with_random_stream(state(R0),
                 with_shared(
                     findall(V, ( between(1, N, I), arg(I, Ws, Wi),
                                  nb_link_world_shared(Wi, Sh),
                                  (   M:'$ddc_tmp'(Id, q, Wi, X) -> V = X ; V = none ),
                                  nb_set_world_shared(Wi, none),
                                  nb_set_world_pure(Wi, false) ),
                             Values)),
                 R1),
        retractall(M:'$ddc_tmp'(Id, _, _, _))),
    nb_set_particles_rng(State, R1).

shared_store_or_none(Sh, SS) :-
    (   Sh == none -> SS = none ; shared_store(Sh, SS) ).

%   stored_value(+I, +Ws, +SS, +Key, -Val): particle I's value of Key, its
%   own first, then the shared one (in store SS, or none), as read_key/4
%   finds it; fails if neither holds one.
stored_value(I, Ws, SS, Key, Val) :-
    arg(I, Ws, W),
    world_store(W, S),
    (   store_get(S, Key, Val0) -> Val = Val0
    ;   SS \== none, store_get(SS, Key, Val)
    ).

first_row_width(I, N, Ws, SS, Key, Width) :-
    I =< N,
    stored_value(I, Ws, SS, Key, Val),
    (   Val == '$undef'
    ->  I1 is I+1,
        first_row_width(I1, N, Ws, SS, Key, Width)
    ;   row_width(Val, Width)
    ).

stored_rows(I, N, Ws, SS, Key, Width, Fs) :-
    (   I > N
    ->  Fs = []
    ;   stored_value(I, Ws, SS, Key, Val),
        (   Val == '$undef'
        ->  nan_row(Width, Fs, Fs1)
        ;   float_row(Val, Width, Fs, Fs1)
        ),
        I1 is I+1,
        stored_rows(I1, N, Ws, SS, Key, Width, Fs1)
    ).
