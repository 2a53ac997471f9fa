/*  ddc_filter.pl -- the particle filter of the DDC engine.

    Included by ddc.pl (this file is part of module ddc).  Python owns the
    weights and the resampling choices; Prolog owns the particles: N
    worlds, each holding the values of time t (and the untimed ones), kept
    in a global variable named by the filter handle, of a Prolog engine of
    the filter's own that any thread may run (filter_new/5: "Threads and
    reloads").

    Final API (as agreed with the Python side):

      filter_new(+ProgramFile, +N, +Seed, -Filter)
      filter_step(+Filter, +Observations, +Actions, -LogWeights)
      filter_undo(+Filter)
      filter_resample(+Filter, +Indices)
      filter_holds(+Filter, +Goal, -Flags)
      filter_values(+Filter, +Template, +Goal, -Values)
      filter_time(+Filter, -T)
      filter_size(+Filter, -N)
      filter_free(+Filter)

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
    in ddc.pl).  Step and resample keep the previous particles for one
    filter_undo/1.  A step either completes for all particles or changes
    nothing.

    Threads (filter_new/5 option threads(K)): the first particle is stepped
    alone (it finds the values every particle shares, and a step in which
    nothing else is left is settled at once); the others are split into K
    contiguous groups, the first stepped by the calling thread, each other
    one by a worker thread (kept for the process) on a copy of its particles
    and of the shared values, drawing from a random stream seeded (after
    the first particle) from the filter's.  The copies come back into the
    filter's particles and their newly shared values join its own
    (step_groups/9).  K is part of the seed: the same K gives the same
    particles on any machine.
*/

:- use_module(library(terms), [mapsubterms/3]).

%!  filter_new(+ProgramFile, +N, +Seed, -Filter) is det.
%
%   Compiles ProgramFile into a module of the filter's own, seeds the
%   random generator with Seed and creates N particles at time 0: every
%   h:0 clause whose body holds is sampled (and h:0 derived atoms
%   materialised); h:t clauses stay lazy.  Filter is an atom, valid in
%   every thread (see "Threads and reloads" below).
filter_new(File, N, Seed, F) :-
    filter_new(File, N, Seed, [], F).

%!  filter_new(+ProgramFile, +N, +Seed, +Options, -Filter) is det.
%
%   As filter_new/4.  Options:
%     - share(false): compute every value in every particle, none once for
%       all (see "Shared values" in ddc.pl): the same particles, slower; for
%       comparison.
%     - threads(K) (default 1): a step's particles after the first are
%       split into K groups, stepped at the same time by K threads (the
%       calling one and K-1 others), each drawing from its own random
%       stream seeded from the filter's.  The particles depend on Seed and
%       K, not on the machine; K = 1 steps them one after the other in the
%       calling thread.
%     - engine(E): auto (the default: batched if the program is in the
%       batched engine's fragment, else per_particle), batched
%       (ddc_batch.pl: each clause evaluated once for a batch of
%       particles; a program outside its fragment is an error naming the
%       clause) or per_particle (this file: one particle at a time).
%       The batched engine gives other particles from the same seed (its
%       draws come clause by clause), ignores share, and splits the
%       particles into threads(K) groups stepped at the same time.
%
%   Threads and reloads: the filter's particles live in a Prolog engine
%   of their own (engine_create/3), which the thread that calls a filter
%   predicate runs for the length of the call; so a filter made in one
%   thread can be stepped and queried in any other, and gives the same
%   particles whichever thread calls it.  Calls on one filter are taken
%   one at a time (a mutex named by the filter); calls on different
%   filters run at the same time.  The filter's program is compiled into
%   a module of its own (ProgramFile#filterK), so ddc_load/2 of the same
%   file, or another filter of it, does not change it: a reload takes
%   effect for the filters made after it.  filter_free/1 frees the engine
%   and the module.
filter_new(File, N, Seed, Options, F) :-
    must_be(list, Options),
    option(share(Share), Options, true),
    must_be(boolean, Share),
    option(threads(K), Options, 1),
    must_be(positive_integer, K),
    option(engine(Engine), Options, auto),
    must_be(oneof([per_particle, batched, auto]), Engine),
    must_be(positive_integer, N),
    must_be(integer, Seed),
    resolve_file(File, Abs),
    new_filter_name(F, Id),
    format(atom(M), '~w#filter~w', [Abs, Id]),
    (   catch(( load_program(Abs, M),
                engine_create(_, filter_server, E),
                assertz(filter_engine_(F, E, M, Abs)),
                filter_call(F, engine_filter_new(F, M, Abs, N, Seed, Share, K, Engine)) ),
              Error,
              ( discard_filter(F, M), throw(Error) ))
    ->  true
    ;   discard_filter(F, M),
        fail
    ).

%   discard_filter(+F, +M): what a filter_new/5 that did not complete made.
discard_filter(F, M) :-
    filter_free(F),
    unload_program(M).

%   engine_filter_new(+F, +M, +Abs, +N, +Seed, +Share, +K, +Engine): in
%   F's engine, its particles (a global variable of the engine named F).
engine_filter_new(F, M, Abs, N, Seed, Share, K, Engine) :-
    (   Engine \== per_particle,
        program_items(M, Items),
        (   Engine == batched
        ->  batch_check_program(Items, Abs)
        ;   catch(batch_check_program(Items, Abs), error(ddc(batched_unsupported(_), _), _), fail)
        )
    ->  batch_new(M, Items, N, Seed, K, BS),
        nb_setval(F, bfilter(none, none)),
        nb_getval(F, Holder),
        batch_keep(BS, Kept),
        nb_linkarg(1, Holder, Kept)
    ;   particle_filter_new(M, N, Seed, Share, K, F)
    ).

new_filter_name(F, Id) :-
    flag(ddc_filter_id, Id, Id+1),
    atom_concat('$ddc_particles_', Id, F).

%   filter_engine_(?Filter, ?Engine, ?Module, ?File): the engine holding
%   Filter's particles, the module of its program and the program's file.
:- dynamic filter_engine_/4.

%   filter_server: the goal of a filter's engine: runs each goal posted to
%   it (engine_post/3), answering true(Goal) (its first solution), false
%   or error(E).  The engine's stacks are reclaimed between goals; the
%   particles are in its global variables.
filter_server :-
    repeat,
    engine_fetch(Goal),
    (   catch(Goal, E, true)
    ->  (   var(E) -> Reply = true(Goal) ; Reply = error(E) )
    ;   Reply = false
    ),
    engine_yield(Reply),
    fail.

%!  filter_call(+Filter:atom, :Goal) is semidet.
%
%   Runs Goal (a call of a filter predicate on Filter, or any goal that
%   must see its engine, such as the profiler's) in Filter's engine, by
%   the calling thread, once no other thread runs it; the first solution's
%   bindings come back (copied).  Errors name the program's file where
%   they named the filter's module; an unknown Filter is
%   error(ddc(unknown_filter(Filter), query), _).  Not exported: called as
%   ddc:filter_call/2.
filter_call(F, Goal) :-
    (   atom(F)
    ->  with_mutex(F, (   filter_engine_(F, E, M, File)
                      ->  engine_post(E, Goal, Reply)
                      ;   Reply = unknown
                      ))
    ;   Reply = unknown
    ),
    filter_reply(Reply, F, Goal, M, File).

filter_reply(true(Goal), _, Goal, _, _).
filter_reply(error(E0), _, _, M, File) :-
    mapsubterms(module_file(M, File), E0, E),
    throw(E).
filter_reply(unknown, F, _, _, _) :-
    throw(error(ddc(unknown_filter(F), query), _)).

module_file(M, File, X, File) :-
    X == M.

%   outside_filter(+F): the caller is not F's engine (a filter predicate
%   called there runs on the particles; called elsewhere, it is posted to
%   the engine).
outside_filter(F) :-
    \+ ( engine_self(E), filter_engine_(F, E, _, _) ).

%   batch_filter(+F, -Holder): F is a batched filter, Holder its
%   bfilter(State, Previous) (updated in place).
batch_filter(F, H) :-
    atom(F), nb_current(F, H), H = bfilter(_, _).

batch_commit(H, S0, S) :-
    batch_keep(S, Kept),
    nb_linkarg(2, H, S0),
    nb_linkarg(1, H, Kept).

particle_filter_new(M, N, Seed, Share, K, F) :-
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
    nb_setval(F, filter(M, N, 0, Ws, none, R, Sh)).

%   The values all particles agree on (see "Shared values" in ddc.pl) and
%   the keys some particle holds a value of its own for.
%   sh(Shared, Impure, RawKeys, Share, Settled, Threads): RawKeys, the
%   untimed copies of this step's observations; Share false: only the
%   observations are shared; Settled: how many steps were settled
%   (step_particles/8); Threads: the groups a step is split into.
new_shared(Share, K, sh(Shared, Impure, [], Share, 0, K)) :-
    store_new(Shared),
    store_new(Impure).

%   A particle's own store is not indexed (particle_store/1).
init_particle(M, Sh, W) :-
    new_world(M, 0, -1, [], W),
    particle_store(S),
    nb_setarg(1, W, S),
    nb_linkarg(14, W, Sh),
    sweep(W, 0),
    nb_setarg(14, W, none),
    nb_setarg(15, W, false),
    nb_setarg(4, W, 0).

%   particle_store(-S): a particle's own store.  It holds what a particle
%   has of its own, few keys even when the shared store holds many: a
%   non-ground read scans it as fast as an index would find its keys, and
%   the index would cost an entry per insertion and make every particle
%   larger to copy (measured: a hidden-ball step of too.pl at N = 1000,
%   one thread, 118.5 -> 110.8 ms; bench/filter_step.py 194 -> 174 ms).
particle_store(S) :-
    store_new(S, false).

%   filter_state(+F, -State): a per-particle filter's state; outside F's
%   engine, a copy of it (for tests that read the particles' stores).
filter_state(F, S) :-
    atom(F), outside_filter(F), !,
    filter_call(F, filter_state(F, S)).
filter_state(F, S) :-
    (   atom(F), nb_current(F, S0), S0 = filter(_, _, _, _, _, _, _)
    ->  S = S0
    ;   throw(error(ddc(unknown_filter(F), query), _))
    ).

%   Each filter owns its random generator state: a filter's draws do not
%   depend on what other filters or queries did in between.
with_rng(R, Goal, R1) :-
    random_property(state(Saved)),
    set_random(state(R)),
    call_cleanup(( Goal, random_property(state(R1)) ),
                 set_random(state(Saved))).

%!  filter_engine(+Filter, -Engine) is det.
%
%   The engine that steps Filter's particles: batched or per_particle.
filter_engine(F, E) :-
    outside_filter(F), !,
    filter_call(F, filter_engine(F, E)).
filter_engine(F, E) :-
    (   batch_filter(F, _) -> E = batched
    ;   filter_state(F, _), E = per_particle
    ).

%!  filter_time(+Filter, -T) is det.
filter_time(F, T) :-
    outside_filter(F), !,
    filter_call(F, filter_time(F, T)).
filter_time(F, T) :-
    batch_filter(F, bfilter(S, _)), !,
    batch_time(S, T).
filter_time(F, T) :-
    filter_state(F, filter(_, _, T, _, _, _, _)).

%!  filter_size(+Filter, -N) is det.
filter_size(F, N) :-
    outside_filter(F), !,
    filter_call(F, filter_size(F, N)).
filter_size(F, N) :-
    batch_filter(F, bfilter(S, _)), !,
    batch_size(S, N).
filter_size(F, N) :-
    filter_state(F, filter(_, N, _, _, _, _, _)).

%!  filter_statistics(+Filter, -Stats) is det.
%
%   Stats: [particles(N), time(T), shared(S), own(O), settled_steps(K)]: S
%   values held once for all particles (see "Shared values" in ddc.pl), O
%   values held by the particles themselves (summed over particles), K
%   steps in which the particles agreed on everything new (computed once).
%   A batched filter: [particles(N), time(T), engine(batched)].
filter_statistics(F, S) :-
    outside_filter(F), !,
    filter_call(F, filter_statistics(F, S)).
filter_statistics(F, [particles(N), time(T), engine(batched)]) :-
    batch_filter(F, bfilter(S, _)), !,
    batch_size(S, N),
    batch_time(S, T).
filter_statistics(F, [particles(N), time(T), shared(S), own(O), settled_steps(K)]) :-
    filter_state(F, filter(_, N, T, Ws, _, _, sh(Shared, _, _, _, K, _))),
    store_size(Shared, S),
    aggregate_all(sum(C), ( between(1, N, I), arg(I, Ws, W), arg(1, W, St), store_size(St, C) ), O).

%!  filter_free(+Filter) is det.
%
%   Frees Filter's particles (its engine) and its program's module; a
%   filter already freed, or never made, is left alone.
filter_free(F) :-
    (   atom(F), filter_engine_(F, _, _, _)
    ->  with_mutex(F, (   retract(filter_engine_(F, E, M, _))
                      ->  engine_destroy(E),
                          unload_program(M)
                      ;   true
                      ))
    ;   true
    ).

%!  filter_step(+Filter, +Observations, +Actions, -LogWeights) is det.
%
%   Advances every particle from t to t+1 (see the file header).
%   Observations: ground terms `h ~= v` (weighted) or plain facts;
%   Actions: ground facts.  LogWeights: N floats (-inf where the
%   observations are impossible).  Throws
%   error(ddc(no_observation_clause(Obs), ...)) if no clause defines an
%   observation in some particle, and leaves the filter unchanged on any
%   error.
filter_step(F, Obs, Acts, LogWs) :-
    outside_filter(F), !,
    filter_call(F, filter_step(F, Obs, Acts, LogWs)).
filter_step(F, Obs, Acts, LogWs) :-
    batch_filter(F, H), !,
    step_input(Obs, Acts, Weighted, Facts),
    arg(1, H, S0),
    batch_step(S0, Weighted, Facts, step(S, LogWs)),
    batch_commit(H, S0, S).
filter_step(F, Obs, Acts, LogWs) :-
    filter_state(F, State),
    State = filter(M, N, T, Ws0, _, R0, Sh0),
    step_input(Obs, Acts, Weighted, Facts0),
    T1 is T+1,
    M:'$ddc_info'(Info),
    group_facts(Facts0, Facts),
    maplist(observation_key(Info, T1), Weighted, Keys),
    scratch_copy(F, Ws0, Sh0, Ws, Sh),
    record_observations(Sh, T, Keys),
    with_rng(R0, with_shared(step_particles(Ws, N, M, T1, Keys, Facts, Sh, LogWs, Agreed)), R1),
    share_agreed(Ws, N, Sh, T1, Agreed),
    commit(F, State, T1, Ws, Sh, T, Ws0, Sh0, R1).

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
share_agreed(Ws, N, sh(Shared, Impure, _, true, _, _), T, Agreed) :-
    !,
    findall(K, ( store_match(Impure, K, _), own_key_at(K, T) ), Ks),
    arg(1, Ws, W1),
    arg(1, W1, S1),
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
    ;   Sh = sh(_, Impure, _, true, _, _)
    ->  arg(Lo, Ws, W),
        arg(1, W, S),
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
    arg(1, Sh, Shared),
    (   store_get(Shared, '$moved'(T), Keys0) -> Keys = Keys0 ; Keys = [] ).

own_key_at(_-T, T).
own_key_at('$mat'(_, T), T).
own_key_at('$memo'(_, T), T).

agreed(I, N, Ws, K, V) :-
    (   I > N
    ->  true
    ;   arg(I, Ws, W),
        arg(1, W, S),
        store_get(S, K, V1),
        V1 == V,
        I1 is I+1,
        agreed(I1, N, Ws, K, V)
    ).

%   step_particles(+Ws, +N, +M, +T1, +Keys, +Facts, +Sh, -LogWs): steps
%   every particle.  If the first particle's step left nothing of its own
%   (every observation's weight, every transition clause and every derived
%   atom of t+1 shared), every other particle's step would only find the
%   same shared values: each gets the first one's weight and is only moved
%   to t+1 (a frame in which the particles agree costs next to nothing).
%   Else the others are stepped in groups (step_groups/10).  Agreed: see
%   share_agreed/5.
step_particles(Ws, N, M, T1, Keys, Facts, Sh, [LW1|LWs], Agreed) :-
    own_particle(Ws, 1, W1),
    nb_setarg(13, W1, true),
    step_particle(W1, T1, Keys, Facts, Sh, LW1),
    arg(6, Sh, K),
    group_seeds(K, Seeds),              % drawn in any case: the draws after
    (   settled(M, Sh, T1, Keys)        % do not depend on settling
    ->  arg(5, Sh, S0),
        S is S0+1,
        nb_setarg(5, Sh, S),
        arg(7, W1, DX),
        T is T1-1,
        moved_keys(Sh, T, Moved),
        findall(LW1, ( between(2, N, I), own_particle(Ws, I, W),
                       settled_step(W, T1, Facts, LW1, DX, Moved) ), LWs),
        Agreed = none
    ;   plan_sweep(M, Sh, T1),
        step_groups(Seeds, Ws, N, M, T1, Keys, Facts, Sh, LWs, Agreed)
    ).

%   group_seeds(+K, -Seeds): a seed for each group but the first (which
%   goes on with the filter's own random stream).
group_seeds(K, Seeds) :-
    K1 is K-1,
    length(Seeds, K1),
    maplist(random_seed, Seeds).

random_seed(S) :-
    random_between(0, 0x3fffffffffffffff, S).

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
    length(Others, KO),
    numlist(1, KO, Tags),
    message_queue_create(Q),
    setup_call_cleanup(
        maplist(start_group(Q, Ws, T1, Keys, Facts, Sh), Tags, Seeds, Others),
        (   catch(( step_range(Lo, Hi, Ws, M, T1, Keys, Facts, Sh, LWs0),
                     group_agreement(Ws, Lo, Hi, Sh, T1, Agreed0) ), E, true),
            maplist(group_result(Q), Tags, Results)
        ),
        message_queue_destroy(Q)),      % (a worker still busy after an abort
                                        % finds the queue gone, and goes on)
    (   nonvar(E) -> throw(E) ; true ),
    maplist(join_particles(Ws), Others, Results, GLWss),
    maplist(join_shared(Ws, Sh), Others, Results),
    maplist(result_agreement, Results, GAgreed),
    append([LWs0|GLWss], LWs).

result_agreement(done(_, _, _, Agreed), Agreed).

%   group_bounds(+From, +To, +K, -Bounds): From..To in K contiguous groups
%   Lo-Hi of sizes differing by at most one (empty ones left out).
group_bounds(From, To, K, Bounds) :-
    Size is To-From+1,
    findall(Lo-Hi,
            ( between(0, K, G0), G0 < K,
              Lo is From + (Size*G0) // K,
              Hi is From + (Size*(G0+1)) // K - 1,
              Hi >= Lo ),
            Bounds).

%   start_group(+Q, +Ws, ..., +Tag, +Seed, +Lo-Hi): sends group Tag's
%   particles (copied by the message) to worker thread Tag, which answers
%   on Q.
start_group(Q, Ws, T1, Keys, Facts, Sh, Tag, Seed, Lo-Hi) :-
    sub_vector(Lo, Hi, Ws, L),
    GWs =.. [ws|L],
    group_thread(Tag, Thread),
    thread_send_message(Thread, group_job(Q, Tag, Seed, Lo, GWs, T1, Keys, Facts, Sh)).

sub_vector(I, Hi, Ws, L) :-
    (   I > Hi
    ->  L = []
    ;   arg(I, Ws, W),
        L = [W|L1],
        I1 is I+1,
        sub_vector(I1, Hi, Ws, L1)
    ).

%   group_thread(+Tag, -Thread): the worker thread for groups Tag.  Workers
%   are kept for the life of the process (a new thread for every step would
%   grow its stacks from nothing each time) and shared by all filters: a
%   worker steps one group at a time.
group_thread(Tag, Alias) :-
    atom_concat('$ddc_group_worker_', Tag, Alias),
    with_mutex('$ddc_group_workers',
               (   catch(thread_property(Alias, status(running)), _, fail)
               ->  true
               ;   thread_create(group_loop, _, [alias(Alias), detached(true)])
               )).

%   A worker: steps the groups it is sent, one after the other, and sends
%   back the stepped particles, their log weights and the shared values
%   (or the error).
group_loop :-
    thread_get_message(Job),
    (   Job = group_job(Q, Tag, Seed, Lo, GWs, T1, Keys, Facts, Sh)
    ->  functor(GWs, _, Len),
        catch(( set_random(seed(Seed)),
                with_shared(step_range_at(1, Len, Lo, held, GWs, T1, Keys, Facts, Sh, LWs)),
                group_agreement(GWs, 1, Len, Sh, T1, Agreed),
                Out = done(GWs, Sh, LWs, Agreed)
              ), E, Out = error(E)),
        catch(thread_send_message(Q, Tag-Out), _, true)
    ;   true
    ),
    group_loop.

group_result(Q, Tag, Out) :-
    thread_get_message(Q, Tag-Out).

%   The particles a worker stepped replace their originals in Ws (all
%   groups first: joining shared values may add to any group's particles).
join_particles(Ws, Lo-_, done(GWs, _, GLWs, _), GLWs) :-
    !,
    functor(GWs, _, Len),
    forall(between(1, Len, J),
           ( I is Lo+J-1, arg(J, GWs, W), nb_linkarg(I, Ws, W) )).
join_particles(_, _, error(E), _) :-
    throw(E).

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
    Sh = sh(Shared, Impure, _, _, _, _),
    GSh = sh(GShared, GImpure, _, _, _, _),
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
    arg(1, W, S),
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
                  nb_setarg(13, W, Check),
                  step_particle(W, T1, Keys, Facts, Sh, LW) ), LWs).

settled(M, sh(Shared, _, _, true, _, _), T1, Keys) :-
    forall(member(k(X, T, _, _), Keys),
           store_get(Shared, '$w'(X, T), w(_, _))),
    forall(( M:'$sweep'(rv, K, X, Id), sweep_kind(K, T1), \+ X = observation(_) ),
           store_get(Shared, '$swept'(Id, T1), _)),
    forall(( M:'$sweep'(der, K, N/A, Sw), Sw = sw(_, eager, _, _, T1, _), sweep_kind(K, T1) ),
           store_get(Shared, '$mat'(N/A, T1), _)).

%   What step_particle/6 would do to a particle once settled/4 holds.
settled_step(W, T1, Facts, LW, DX, Moved) :-
    arg(1, W, S),
    T is T1-1,
    store_prune(S, T, Moved),
    nb_setarg(3, W, T1),
    nb_linkarg(12, W, Facts),
    nb_setarg(6, W, LW),
    nb_setarg(7, W, DX),
    nb_setarg(4, W, T1).

%   record_observations(+Sh, +T, +Keys): drops the values of times before T
%   and the previous step's observations from the shared store and records
%   this step's: an observation's value is the same in every particle.  A
%   timed observation is also recorded untimed, for bodies that read it
%   raw (the original's bodies read observation(x) ~= V untimed), unless
%   the untimed variable has a value already; both go at the next step.
record_observations(Sh, T, Keys) :-
    Sh = sh(Shared, Impure, Raw0, _, _, _),
    store_prune(Shared, T, Raw0),
    store_prune(Impure, T, []),
    foldl(record_observation(Shared), Keys, [], Raw),
    nb_setarg(3, Sh, Raw).

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
commit(F, State, T, Ws, Sh, T0, Ws0, Sh0, R) :-
    nb_setarg(5, State, prev(T0, '$', '$')),
    arg(5, State, Prev),
    nb_linkarg(2, Prev, Ws0),
    nb_linkarg(3, Prev, Sh0),
    nb_linkarg(4, State, Ws),
    nb_linkarg(7, State, Sh),
    nb_setarg(3, State, T),
    nb_setarg(6, State, R),
    atom_concat(F, '$next', FN),
    nb_delete(FN).

%   step_input(+Obs, +Acts, -Weighted, -Facts): a step's input checked
%   (lists of ground items), its weighted observations (h ~= v) and its
%   facts (the actions, then the plain observations).
step_input(Obs, Acts, Weighted, Facts) :-
    must_be(list, Obs),
    must_be(list, Acts),
    forall(member(O, Obs), must_be_ground_item(O)),
    forall(member(A, Acts), must_be_ground_item(A)),
    partition(weighted_observation, Obs, Weighted, PlainObs),
    append(Acts, PlainObs, Facts).

weighted_observation(O) :-
    nonvar(O), O = (_ ~= _).

must_be_ground_item(X) :-
    (   ground(X) -> true ; throw(error(ddc(not_ground(X), query), _)) ).

%   observation_key(+Info, +T1, +Obs, -k(X, T, V, Obs))
observation_key(Info, T1, (H ~= V), k(X, T, V, (H ~= V))) :-
    read_key_code(H, ctx(_, T1, Info, query), X, T, TG),
    call(TG).

step_particle(W, T1, Keys, Facts, Sh, LW) :-
    %   everything before time t (kept until now for queries at t that look
    %   one step back) goes, and so do the values of t now shared
    arg(1, W, S),
    T is T1-1,
    moved_keys(Sh, T, Moved),
    store_prune(S, T, Moved),
    nb_setarg(3, W, T1),
    nb_linkarg(12, W, Facts),           % ground, shared by all particles: no copy
    nb_linkarg(14, W, Sh),              % (unlinked at the end: copies of W never copy Sh)
    nb_setarg(6, W, 0.0),
    nb_setarg(7, W, 0),
    weigh_observations(Keys, W),
    arg(6, W, LW),
    sweep(W, T1),
    nb_setarg(4, W, T1),
    nb_setarg(14, W, none),
    nb_setarg(15, W, false),
    !.

%   Each observation weights the particle once, by the density of its
%   first applicable clause (whose proof sees every observation's value).
weigh_observations([], _).
weigh_observations([k(X, T, V, O)|Ks], W) :-
    (   weigh_key(X, T, V, W, 6)
    ->  weigh_observations(Ks, W)
    ;   throw(error(ddc(no_observation_clause(O), query), _))
    ).

%   sweep(+W, +T): sample every random variable that a transition (or, at
%   T = 0, prior) clause defines at T, and materialise the derived atoms
%   of such clauses.
sweep(W, T) :-
    arg(2, W, M),
    nb_setarg(11, W, sweep),
    (   sweep_plan(W, T, plan(Ids, Ders)) -> true ; sweep_items(M, T, Ids, Ders) ),
    forall(( member(Id, Ids), M:'$sweep'(rv, _, X, Id) ),
           sweep_clause(W, M, Id, X, T)),
    forall(( member(K-NA, Ders), M:'$sweep'(der, K, NA, Sw), Sw = sw(_, eager, _, _, T, W) ),
           materialise(W, M, NA, Sw, T)),
    nb_setarg(11, W, normal).

%   sweep_items(+M, +T, -Ids, -Ders): what a sweep at T goes through, in
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
    arg(14, W, Sh),
    Sh \== none,
    arg(1, Sh, SS),
    store_get(SS, '$plan'(T), Plan).

%   plan_sweep(+M, +Sh, +T): records the plan of step T, after the first
%   particle's sweep.
plan_sweep(M, Sh, T) :-
    arg(1, Sh, SS),
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
%   shared, see "Shared values" in ddc.pl), that holds in every particle:
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
    arg(14, W, Sh),                     % (a particle sweeps only in a step)
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
    arg(4, W, Fz),
    arg(11, W, Mode),
    Fz1 is T-1,
    setup_call_cleanup(( nb_setarg(4, W, Fz1), nb_setarg(11, W, sweep) ),
                       materialise(W, M, NA, Sw, T),
                       ( nb_setarg(4, W, Fz), nb_setarg(11, W, Mode) )).

%   (Sharing the candidates of clauses whose key prefix is clean, as the
%   derived atoms are, was measured slower: those prefixes are one or two
%   fact lookups, cheaper than the shared table's findall and copy.)
sweep_candidate(M, Id, X, T, W) :-
    M:'$sweep_key'(Id, X, T, W).

sweep_kind(trans, T) :- T >= 1.
sweep_kind(persist, T) :- T >= 1.
sweep_kind(fixed(T), T).

%!  filter_undo(+Filter) is det.
%
%   Restores the particles and the time from before the last step (or
%   resampling).  Only one level is kept.
filter_undo(F) :-
    outside_filter(F), !,
    filter_call(F, filter_undo(F)).
filter_undo(F) :-
    batch_filter(F, H), !,
    (   H = bfilter(_, S0), S0 \== none
    ->  nb_linkarg(1, H, S0),
        nb_setarg(2, H, none)
    ;   throw(error(ddc(nothing_to_undo, query), _))
    ).
filter_undo(F) :-
    filter_state(F, filter(M, N, _, _, Prev, R, _)),
    (   Prev = prev(T0, Ws0, Sh0)
    ->  nb_setval(F, filter(M, N, T0, Ws0, none, R, Sh0))
    ;   throw(error(ddc(nothing_to_undo, query), _))
    ).

%!  filter_resample(+Filter, +Indices) is det.
%
%   Particle i (1-based position in Indices) becomes a copy of particle
%   Indices[i] (0-based), as chosen by the caller.
filter_resample(F, Is) :-
    outside_filter(F), !,
    filter_call(F, filter_resample(F, Is)).
filter_resample(F, Is) :-
    batch_filter(F, H), !,
    arg(1, H, S0),
    batch_size(S0, N),
    must_be_indices(Is, N),
    batch_resample(S0, Is, S),
    batch_commit(H, S0, S).
filter_resample(F, Is) :-
    filter_state(F, State),
    State = filter(_, N, T, Ws0, _, R, Sh),
    must_be_indices(Is, N),
    %   findall/3 copies each chosen particle on its own: copies of one
    %   particle are independent worlds; the new set is linked, not copied
    %   again (it holds no variable bound outside it)
    findall(W, ( member(I, Is), I1 is I+1, arg(I1, Ws0, W) ), L),
    Ws =.. [ws|L],
    commit(F, State, T, Ws, Sh, T, Ws0, Sh, R).

must_be_indices(Is, N) :-
    must_be(list(nonneg), Is),
    (   length(Is, N) -> true
    ;   throw(error(ddc(bad_indices(length_differs_from_particles(N)), query), _))
    ),
    (   forall(member(I, Is), I < N) -> true
    ;   throw(error(ddc(bad_indices(index_out_of_range(N)), query), _))
    ).

%!  filter_holds(+Filter, +Goal, -Flags) is det.
%
%   Flags: for each particle 1 if Goal is provable in its world at the
%   current time, else 0.  In Goal, `t` is the current time and an
%   untimed `h ~= V` or derived atom that the program only defines with a
%   time index means h at the current time.  Random variables the proof
%   needs and the particle lacks are sampled and kept in the particle.
filter_holds(F, Goal, Flags) :-
    outside_filter(F), !,
    filter_call(F, filter_holds(F, Goal, Flags)).
filter_holds(F, Goal, Flags) :-
    batch_filter(F, bfilter(S, _)), !,
    batch_query_goal(S, Goal, G),
    batch_holds(S, G, Flags).
filter_holds(F, Goal, Flags) :-
    filter_query(F, Goal, true, Sols),
    maplist(solution_flag, Sols, Flags).

solution_flag(S, B) :-
    (   S == none -> B = 0 ; B = 1 ).

%!  filter_values(+Filter, +Template, +Goal, -Values) is det.
%
%   Values: for each particle Template instantiated by the first solution
%   of Goal, or the atom none.
filter_values(F, Template, Goal, Values) :-
    outside_filter(F), !,
    filter_call(F, filter_values(F, Template, Goal, Values)).
filter_values(F, Template, Goal, Values) :-
    batch_filter(F, bfilter(S, _)), !,
    batch_query_goal(S, Goal, G),
    batch_values(S, Template, G, Values).
filter_values(F, Template, Goal, Values) :-
    filter_query(F, Goal, Template, Values).

%   batch_query_goal(+State, +Goal, -G): Goal with each untimed read or
%   derived atom that the program only defines with a time index read at
%   the current time t (as filter_holds/3 documents).
batch_query_goal(S, Goal, G) :-
    batch_module(S, M),
    M:'$ddc_info'(info(_, DerT, RvU, RvT, _, _, _)),
    current_time_goal(Goal, DerT, RvU, RvT, G).     % (sharing Goal's variables)

current_time_goal(V, _, _, _, V) :- var(V), !.
current_time_goal((A, B), D, U, R, (A1, B1)) :- !,
    current_time_goal(A, D, U, R, A1), current_time_goal(B, D, U, R, B1).
current_time_goal((A ; B), D, U, R, (A1 ; B1)) :- !,
    current_time_goal(A, D, U, R, A1), current_time_goal(B, D, U, R, B1).
current_time_goal((A -> B), D, U, R, (A1 -> B1)) :- !,
    current_time_goal(A, D, U, R, A1), current_time_goal(B, D, U, R, B1).
current_time_goal(\+ A, D, U, R, \+ A1) :- !,
    current_time_goal(A, D, U, R, A1).
current_time_goal(findall(T, A, L), D, U, R, findall(T, A1, L)) :- !,
    current_time_goal(A, D, U, R, A1).
current_time_goal(findall_forward(T, A, L), D, U, R, findall_forward(T, A1, L)) :- !,
    current_time_goal(A, D, U, R, A1).
current_time_goal(X ~= V, _, U, R, G) :-
    callable(X), X \= _:_, functor(X, N, A),
    memberchk(N/A, R), \+ memberchk(N/A, U), !,
    G = (X:t ~= V).
current_time_goal(X, D, _, _, X:t) :-
    callable(X), X \= _:_, X \= (_ ~= _), functor(X, N, A), memberchk(N/A, D), !.
current_time_goal(G, _, _, _, G).

%!  filter_rows(+Filter, +Template, +Goal, -Width, -Floats, -Values) is det.
%
%   The values of filter_values/4 as numbers: if Template, at the first
%   solution of Goal in each particle, is a number or a tuple (A, B, ...)
%   of numbers of the same length Width in every particle that has a
%   solution, Floats is one flat list of N*Width floats, particle by
%   particle (a row of NaNs where Goal has no solution) and Values = [];
%   else Width = 0, Floats = [] and Values is what filter_values(Filter,
%   value(Template), Goal, Values) gives (none where Goal has no solution,
%   value(T) else).  A goal `h ~= V` with template V and ground h (a random
%   variable's values) is read straight from the particles' stores, without
%   building the values, when every particle holds one.
filter_rows(F, Template, Goal, Width, Floats, Values) :-
    outside_filter(F), !,
    filter_call(F, filter_rows(F, Template, Goal, Width, Floats, Values)).
filter_rows(F, Template, Goal, Width, Floats, Values) :-
    \+ batch_filter(F, _),
    filter_state(F, filter(M, N, T, Ws, _, _, Sh)),
    M:'$ddc_info'(Info),
    stored_read(Goal, Template, ctx(_, T, Info, query), Key, V, Tmpl),
    Tmpl == V,
    shared_store(Sh, SS),
    first_row_width(1, N, Ws, SS, Key, Width0),
    stored_rows(1, N, Ws, SS, Key, Width0, Floats0),
    !,
    Width = Width0, Floats = Floats0, Values = [].
filter_rows(F, Template, Goal, Width, Floats, Values) :-
    filter_values(F, value(Template), Goal, Values0),
    (   once(member(value(V1), Values0)),
        row_width(V1, Width1),
        value_rows(Values0, Width1, Floats1)
    ->  Width = Width1, Floats = Floats1, Values = []
    ;   Width = 0, Floats = [], Values = Values0
    ).

value_rows([], _, []).
value_rows([V|Vs], W, Fs) :-
    (   V = value(X)
    ->  float_row(X, W, Fs, Fs1)
    ;   nan_row(W, Fs, Fs1)
    ),
    value_rows(Vs, W, Fs1).

shared_store(Sh, SS) :-
    (   Sh == none -> SS = none ; arg(1, Sh, SS) ).

%   stored_value(+I, +Ws, +SS, +Key, -Val): particle I's value of Key, its
%   own first, then the shared one (in store SS, or none), as read_key/4
%   finds it; fails if neither holds one.
stored_value(I, Ws, SS, Key, Val) :-
    arg(I, Ws, W),
    arg(1, W, S),
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

row_width(V, 1) :- number(V), !.
row_width((A, B), W) :- number(A), row_width(B, W0), W is W0+1.

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

nan_row(0, Fs, Fs) :- !.
nan_row(W, [X|Fs], Fs1) :-
    X is nan,
    W1 is W-1,
    nan_row(W1, Fs, Fs1).

float_row(V, 1, [X|Fs], Fs) :-
    number(V), !,
    X is float(V).
float_row((A, B), W, [X|Fs], Fs1) :-
    W > 1, number(A),
    X is float(A),
    W1 is W-1,
    float_row(B, W1, Fs, Fs1).

filter_literal(Ctx, G, C) :-
    cb(G, Ctx, C).

filter_query(F, Goal, Template, Values) :-
    filter_state(F, State),
    State = filter(M, N, T, Ws, _, R0, Sh),
    M:'$ddc_info'(Info),
    (   stored_read(Goal, Template, ctx(_, T, Info, query), Key, V, Tmpl),
        shared_store(Sh, SS),
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
        with_rng(R0,
                 with_shared(
                     findall(V, ( between(1, N, I), arg(I, Ws, Wi),
                                  nb_linkarg(14, Wi, Sh),
                                  (   M:'$ddc_tmp'(Id, q, Wi, X) -> V = X ; V = none ),
                                  nb_setarg(14, Wi, none),
                                  nb_setarg(15, Wi, false) ),
                             Values)),
                 R1),
        retractall(M:'$ddc_tmp'(Id, _, _, _))),
    nb_setarg(6, State, R1).
