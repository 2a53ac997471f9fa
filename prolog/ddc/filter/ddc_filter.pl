/** <module> The particle filter API of the DDC engine

Part of the DDC engine (ddc.pl is the module users load, and re-exports
this module's API).  The caller owns the weights and the resampling
choices (by the rules of ddc_weights.pl: ddc_belief.pl in swipl,
bridge.Filter in Python); this module owns the particles: N worlds, each holding the values
of time t (and the untimed ones), kept in a global variable named by
the filter handle, of a Prolog engine of the filter's own that any
thread may run (filter_new/5: "Threads and reloads").

API:

  filter_new(+ProgramFile, +N, +Seed, -Filter)
  filter_new(+ProgramFile, +N, +Seed, +Options, -Filter)
  filter_step(+Filter, +Observations, +Actions, -LogWeights)
  filter_undo(+Filter)
  filter_resample(+Filter, +Indices)
  filter_rename(+Filter, +Renaming, +Particles)
  filter_holds(+Filter, +Goal, -Flags)
  filter_values(+Filter, +Template, +Goal, -Values)
  filter_rows(+Filter, +Template, +Goal, -Width, -Floats, -Values)
  filter_time(+Filter, -T)
  filter_engine(+Filter, -Engine)
  filter_size(+Filter, -N)
  filter_statistics(+Filter, -Stats)
  filter_free(+Filter)

Engines.  A filter holds its engine and the engine's state, a record
filter_handle(Engine, Module, State): Engine is per_particle
(ddc_particles.pl, one particle at a time) or batched
(ddc_filter_batched.pl over ddc_batch.pl, each clause evaluated once
for a batch of particles), Module the module implementing it.  Each
engine module defines the same interface, called as Module:Goal on
the engine's State (updated in place):

  engine_step(!State, +WeightedObservations, +Facts, -LogWeights)
  engine_undo(!State)                        (semidet: fails when there
      is nothing to undo; the API raises the error)
  engine_resample(!State, +Indices)          (checked by the API)
  engine_rename(!State, +Moves, +Particles)  (checked by the API: Moves
      the pairs Old-New of a renaming with Old \== New, not empty;
      Particles a sorted list of 1-based indices without repeats, not
      empty)
  engine_holds(!State, +Goal, -Flags)
  engine_values(!State, +Template, +Goal, -Values)
  engine_rows(+State, +Template, +Goal, -Width, -Floats)   (semidet:
      rows read without building the values; else the API makes them
      from engine_values/4)
  engine_packed_rows(+State, +Template, +Goal, -Width, -Rows),
  engine_packed_indices(+State, +Template, +Goal, +Atoms, -Indices)
      (optional, semidet: read straight from the engine's columns into a
      blob of doubles; else the API makes them from engine_values/4)
  engine_time(+State, -T)
  engine_size(+State, -N)
  engine_statistics(+State, -Stats)
  engine_free(+State)

The semantics of a step are in ddc_particles.pl's header (the batched
engine gives the same distribution, from other draws).
*/

:- module(ddc_filter,
          [ filter_new/4,               % +ProgramFile, +N, +Seed, -Filter
            filter_new/5,               % +ProgramFile, +N, +Seed, +Options, -Filter
            filter_step/4,              % +Filter, +Observations, +Actions, -LogWeights
            filter_undo/1,              % +Filter
            filter_resample/2,          % +Filter, +Indices
            filter_rename/3,            % +Filter, +Renaming, +Particles
            filter_holds/3,             % +Filter, +Goal, -Flags
            filter_values/4,            % +Filter, +Template, +Goal, -Values
            filter_rows/6,              % +Filter, +Template, +Goal, -Width, -Floats, -Values
            filter_packed_rows/6,       % +Filter, +Template, +Goal, -Width, -Floats, -Values
            filter_indices/5,           % +Filter, ?Template, +Goal, +Atoms, -Indices
            filter_packed_indices/5,    % +Filter, ?Template, +Goal, +Atoms, -Indices
            filter_time/2,              % +Filter, -T
            filter_engine/2,            % +Filter, -Engine
            filter_size/2,              % +Filter, -N
            filter_statistics/2,        % +Filter, -Stats
            filter_free/1,              % +Filter
            filter_call/2,              % +Filter, :Goal
            filter_state/2,             % +Filter, -State
            filter_engine_/4            % ?Filter, ?Engine, ?Module, ?File
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(option)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module(library(terms), [mapsubterms/3]).
:- use_module('../lang/ddc_records').
:- use_module('../lang/ddc_read', [resolve_file/2]).
:- use_module('../lang/ddc_programs', [load_program/2, unload_program/1, program_items/2]).
:- use_module('../batch/ddc_batch', [batch_check_program/2]).
:- use_module('../runtime/ddc_rows', [values_rows/4]).
:- use_module(ddc_particles, [particles_new/7]).
:- use_module(ddc_filter_batched, [batched_init/6]).
:- use_module('../runtime/ddc_rename', [renaming_moves/2]).

:- use_module('../lang/ddc_ops').

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

:- record_type filter_handle(engine, module, state).

%!  default_threads(-K) is det.
%
%   The groups a step's particles are split into without option
%   threads(K).
default_threads(1).

%!  default_engine(-Engine) is det.
%
%   The engine without option engine(E).
default_engine(auto).

%!  engine_module(?Engine, ?Module) is nondet.
%
%   Module implements the engine interface (see the file header) for
%   Engine.
engine_module(per_particle, ddc_particles).
engine_module(batched, ddc_filter_batched).

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
%       all (see "Shared values" in ddc_world.pl): the same particles,
%       slower; for comparison.
%     - threads(K) (default 1, default_threads/1): a step's particles after the first are
%       split into K groups, stepped at the same time by K threads (the
%       calling one and K-1 others), each drawing from its own random
%       stream seeded from the filter's.  The particles depend on Seed and
%       K, not on the machine; K = 1 steps them one after the other in the
%       calling thread.
%     - engine(E): auto (the default, default_engine/1: batched if the
%       program is in the batched engine's fragment, else per_particle),
%       batched
%       (ddc_batch.pl: each clause evaluated once for a batch of
%       particles; a program outside its fragment is an error naming the
%       clause) or per_particle (ddc_particles.pl: one particle at a
%       time).
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
    default_threads(DefaultThreads),
    option(threads(K), Options, DefaultThreads),
    must_be(positive_integer, K),
    default_engine(DefaultEngine),
    option(engine(Engine), Options, DefaultEngine),
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
%   F's engine, its particles (a global variable of the engine named F,
%   holding F's filter_handle record).
engine_filter_new(F, M, Abs, N, Seed, Share, K, Engine) :-
    (   Engine \== per_particle,
        program_items(M, Items),
        (   Engine == batched
        ->  batch_check_program(Items, Abs)
        ;   catch(batch_check_program(Items, Abs), error(ddc(batched_unsupported(_), _), _), fail)
        )
    ->  engine_module(batched, Module),
        nb_setval(F, filter_handle(batched, Module, batched(none, none))),
        filter_handle(F, _, State),
        batched_init(State, M, Items, N, Seed, K)
    ;   engine_module(per_particle, Module),
        particles_new(F, M, N, Seed, Share, K, State),
        nb_setval(F, filter_handle(per_particle, Module, State))
    ).

new_filter_name(F, Id) :-
    flag(ddc_filter_id, Id, Id+1),
    atom_concat('$ddc_particles_', Id, F).

%!  filter_engine_(?Filter, ?PrologEngine, ?Module, ?File) is nondet.
%
%   The Prolog engine (engine_create/3) holding Filter's particles, the
%   module of its program and the program's file.
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
%   error(existence_error(ddc_filter, Filter), context(PI, _)), PI the
%   predicate indicator of Goal (unknown_filter/2).  Goal runs in this
%   module.  Not exported by ddc.pl: called as ddc:filter_call/2 (or
%   ddc_filter:filter_call/2).
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
filter_reply(unknown, F, Goal, _, _) :-
    (   callable(Goal) -> functor(Goal, Name, Arity), PI = ddc_filter:Name/Arity ; true ),
    unknown_filter(F, PI).

%   unknown_filter(+Filter, ?PI): the ISO error of an API predicate PI
%   called on a Filter that is not (or no longer) a filter.
unknown_filter(F, PI) :-
    throw(error(existence_error(ddc_filter, F),
                context(PI, 'freed, or never created'))).

module_file(M, File, X, File) :-
    X == M.

%   outside_filter(+F): the caller is not F's engine (a filter predicate
%   called there runs on the particles; called elsewhere, it is posted to
%   the engine).
outside_filter(F) :-
    \+ ( engine_self(E), filter_engine_(F, E, _, _) ).


%   filter_handle(+F, -Module, -State): F's engine (the module implementing
%   it) and its state, updated in place.  (In F's engine.)
filter_handle(F, Module, State) :-
    current_handle(F, H),
    filter_handle_module(H, Module),
    filter_handle_state(H, State).

%   current_handle(+F, -H): F's filter_handle record.  (In F's engine.)
current_handle(F, H) :-
    (   atom(F), nb_current(F, H0), H0 = filter_handle(_, _, _)
    ->  H = H0
    ;   unknown_filter(F, _)
    ).

%!  filter_state(+Filter, -State) is det.
%
%   The state of Filter's engine (ddc_particles.pl's particles record, or
%   ddc_filter_batched.pl's batched record); outside Filter's engine, a
%   copy of it (for tests that read the particles' stores).
filter_state(F, S) :-
    atom(F), outside_filter(F), !,
    filter_call(F, filter_state(F, S)).
filter_state(F, S) :-
    filter_handle(F, _, S).

%!  filter_engine(+Filter, -Engine) is det.
%
%   The engine that steps Filter's particles: batched or per_particle.
filter_engine(F, E) :-
    outside_filter(F), !,
    filter_call(F, filter_engine(F, E)).
filter_engine(F, E) :-
    current_handle(F, H),
    filter_handle_engine(H, E).

%!  filter_time(+Filter, -T) is det.
filter_time(F, T) :-
    outside_filter(F), !,
    filter_call(F, filter_time(F, T)).
filter_time(F, T) :-
    filter_handle(F, E, S),
    E:engine_time(S, T).

%!  filter_size(+Filter, -N) is det.
filter_size(F, N) :-
    outside_filter(F), !,
    filter_call(F, filter_size(F, N)).
filter_size(F, N) :-
    filter_handle(F, E, S),
    E:engine_size(S, N).

%!  filter_statistics(+Filter, -Stats) is det.
%
%   Stats: [particles(N), time(T), shared(S), own(O), settled_steps(K)]: S
%   values held once for all particles (see "Shared values" in
%   ddc_world.pl), O values held by the particles themselves (summed over
%   particles), K steps in which the particles agreed on everything new
%   (computed once).  A batched filter: [particles(N), time(T),
%   engine(batched), columns(B)], B foreign (the compiled column
%   library) or prolog (ddc_batch_col.pl).
filter_statistics(F, S) :-
    outside_filter(F), !,
    filter_call(F, filter_statistics(F, S)).
filter_statistics(F, Stats) :-
    filter_handle(F, E, S),
    E:engine_statistics(S, Stats).

%!  filter_free(+Filter) is det.
%
%   Frees Filter's particles (its engine) and its program's module; a
%   filter already freed, or never made, is left alone.
filter_free(F) :-
    (   atom(F), filter_engine_(F, _, _, _)
    ->  with_mutex(F, (   retract(filter_engine_(F, E, M, _))
                      ->  catch(ignore(engine_call_free(E, F)), _, true),
                          engine_destroy(E),
                          unload_program(M)
                      ;   true
                      ))
    ;   true
    ).

%   engine_call_free(+PrologEngine, +F): the filter engine's engine_free/1,
%   run in F's Prolog engine (fails if F has no state yet).
engine_call_free(E, F) :-
    engine_post(E, ( nb_current(F, H), H = filter_handle(_, Module, S), Module:engine_free(S) ),
                Reply),
    Reply = true(_).

%!  filter_step(+Filter, +Observations, +Actions, -LogWeights) is det.
%
%   Advances every particle from t to t+1 (see ddc_particles.pl's header).
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
    filter_handle(F, E, S),
    step_input(Obs, Acts, Weighted, Facts),
    E:engine_step(S, Weighted, Facts, LogWs).

%!  filter_undo(+Filter) is det.
%
%   Restores the particles and the time from before the last step (or
%   resampling).  Only one level is kept.
filter_undo(F) :-
    outside_filter(F), !,
    filter_call(F, filter_undo(F)).
filter_undo(F) :-
    filter_handle(F, E, S),
    (   E:engine_undo(S)
    ->  true
    ;   throw(error(permission_error(undo, ddc_filter, F),
                    context(ddc_filter:filter_undo/1,
                            'no step or resampling to undo: one level is kept')))
    ).

%!  filter_resample(+Filter, +Indices) is det.
%
%   Particle i (1-based position in Indices) becomes a copy of particle
%   Indices[i] (0-based), as chosen by the caller.
filter_resample(F, Is) :-
    outside_filter(F), !,
    filter_call(F, filter_resample(F, Is)).
filter_resample(F, Is) :-
    filter_handle(F, E, S),
    E:engine_size(S, N),
    must_be_indices(Is, N),
    E:engine_resample(S, Is).

must_be_indices(Is, N) :-
    indices_below(Is, N, 0, K), K =:= N, !.      % (the usual case, in one pass)
must_be_indices(Is, N) :-
    must_be(list(nonneg), Is),
    (   length(Is, N) -> true
    ;   bad_indices(N, Is, 'not one index per particle')
    ),
    (   forall(member(I, Is), I < N) -> true
    ;   bad_indices(N, Is, 'an index out of range')
    ).

%   bad_indices(+N, +Indices, +Why): the ISO error of resampling indices
%   that are not N indices in 0..N-1.
bad_indices(N, Is, Why) :-
    N1 is N - 1,
    format(atom(Msg), '~w: ~D indices in 0..~D expected', [Why, N, N1]),
    throw(error(domain_error(particle_indices(N), Is),
                context(ddc_filter:filter_resample/2, Msg))).

indices_below(Is, _, _, _) :- var(Is), !, fail.
indices_below([], _, K, K).
indices_below([I|Is], N, K0, K) :-
    integer(I), I >= 0, I < N,
    K1 is K0+1,
    indices_below(Is, N, K1, K).

%!  filter_rename(+Filter, +Renaming:list(pair), +Particles) is det.
%
%   In each particle of Particles (a list of 1-based indices, repeats
%   ignored, or `all`), the constants Old of Renaming (a list Old-New of
%   atoms, each Old once, the News the same set as the Olds: a
%   permutation; pairs Old-Old are allowed) are named New: every value the
%   particle holds, of the current time t, of t-1 (which the next step's
%   :t reads see) and untimed, has every Old replaced by its New, in its
%   key (the arguments of a random variable or derived atom: pos(mug_1),
%   occluded_by(ball_1, mug_1)) and in the value itself (a value mug_1,
%   or an atom inside a value).  The next filter_step/4 goes on from the
%   renamed worlds exactly as if the constants had always been named so
%   in those particles.  Names of random variables, predicates and
%   functors are not constants and stay; so do the program's clauses, the
%   facts of the current step (actions, plain observations: the input of
%   the step, replaced at the next one) and the untimed copies of the
%   step's observations that are dropped at the next step.  The other
%   particles keep their values (the same values, read as before);
%   weights are Python's and untouched.
%
%   A rename changes the state the next step starts from: filter_undo/1
%   after a rename and a step undoes the step and keeps the rename; after
%   a rename with no step since, it goes back to before the last step (or
%   resampling), as it would have without the rename.
%
%   Cost: proportional to the values the renamed particles hold (their
%   own and the shared ones they read; a value held once for all
%   particles that the rename changes becomes each particle's own, one
%   entry per particle).  Meant for rare events (an ambiguous
%   association); a filter that never renames pays nothing for it.
%
%   @error type_error(list, Renaming), type_error(pair, Item),
%          type_error(atom, Name) for a malformed Renaming;
%          domain_error(permutation, Renaming) if an Old occurs twice or
%          the News are not the Olds; type_error(integer, I) and
%          domain_error(between(1, N), I) for a bad particle index
%          (all with context(filter_rename/3, _)).
filter_rename(F, Renaming, Particles) :-
    outside_filter(F), !,
    filter_call(F, filter_rename(F, Renaming, Particles)).
filter_rename(F, Renaming, Particles) :-
    filter_handle(F, E, S),
    E:engine_size(S, N),
    in_context(filter_rename/3, ( must_be_renaming(Renaming),
                                  rename_particles(Particles, N, Is) )),
    renaming_moves(Renaming, Moves),
    (   ( Moves == [] ; Is == [] )
    ->  true
    ;   E:engine_rename(S, Moves, Is)
    ).

%   in_context(+PI, :Goal): Goal, its errors raised with context(PI, _)
%   (and the message they had, if any).
in_context(PI, Goal) :-
    catch(Goal, error(Formal, Ctx0),
          ( error_context(Ctx0, PI, Ctx), throw(error(Formal, Ctx)) )).

error_context(Ctx, PI, context(PI, _)) :- var(Ctx), !.
error_context(context(P, Msg), PI, context(PI, Msg)) :- var(P), !.
error_context(Ctx, _, Ctx).

%   must_be_renaming(+Renaming): Old-New atom pairs, a permutation.
must_be_renaming(R) :-
    must_be(list, R),
    forall(member(P, R), must_be_rename_pair(P)),
    pairs_keys_values(R, Olds, News),
    msort(Olds, Sorted),
    (   sort(Olds, Sorted)
    ->  true
    ;   throw(error(domain_error(permutation, R),
                    context(_, 'a name is renamed twice')))
    ),
    (   msort(News, Sorted)
    ->  true
    ;   throw(error(domain_error(permutation, R),
                    context(_, 'the new names are not the old ones')))
    ).

must_be_rename_pair(P) :-
    (   nonvar(P), P = Old-New
    ->  must_be(atom, Old),
        must_be(atom, New)
    ;   var(P)
    ->  instantiation_error(P)
    ;   type_error(pair, P)
    ).

must_be_particle(I, N) :-
    must_be(integer, I),
    (   between(1, N, I) -> true ; domain_error(between(1, N), I) ).

%   rename_particles(+Particles, +N, -Is): the 1-based indices of
%   Particles (all, or a list), sorted, without repeats.
rename_particles(Ps, N, Is) :-
    (   Ps == all
    ->  numlist(1, N, Is)
    ;   must_be(list, Ps),
        forall(member(I, Ps), must_be_particle(I, N)),
        sort(Ps, Is)
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
    filter_handle(F, E, S),
    E:engine_holds(S, Goal, Flags).

%!  filter_values(+Filter, +Template, +Goal, -Values) is det.
%
%   Values: for each particle Template instantiated by the first solution
%   of Goal, or the atom none.
filter_values(F, Template, Goal, Values) :-
    outside_filter(F), !,
    filter_call(F, filter_values(F, Template, Goal, Values)).
filter_values(F, Template, Goal, Values) :-
    filter_handle(F, E, S),
    E:engine_values(S, Template, Goal, Values).

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
    filter_handle(F, E, S),
    (   E:engine_rows(S, Template, Goal, Width0, Floats0)
    ->  Width = Width0, Floats = Floats0, Values = []
    ;   filter_values(F, value(Template), Goal, Values0),
        values_rows(Values0, Width, Floats, Values)
    ).

%!  filter_packed_rows(+Filter, +Template, +Goal, -Width, -Floats, -Values) is det.
%
%   filter_rows/6, with Floats, where the engine can read them straight
%   from its columns (the batched engine's engine_packed_rows/5, with its
%   column library), a blob of doubles (ddc_batch_col.pl's
%   col_pack_rows/3): an atom, not copied out of the filter's engine as a
%   list of floats is, whose doubles a reader in another language has
%   copied into its memory at once (the Python bridge: 10,000 particles'
%   positions are 30,000 floats).
filter_packed_rows(F, Template, Goal, Width, Floats, Values) :-
    outside_filter(F), !,
    filter_call(F, filter_packed_rows(F, Template, Goal, Width, Floats, Values)).
filter_packed_rows(F, Template, Goal, Width, Floats, Values) :-
    filter_handle(F, E, S),
    (   current_predicate(E:engine_packed_rows/5),
        E:engine_packed_rows(S, Template, Goal, Width0, Rows)
    ->  Width = Width0, Floats = Rows, Values = []
    ;   filter_rows(F, Template, Goal, Width, Floats, Values)
    ).

%!  filter_indices(+Filter, ?Template, +Goal, +Atoms:list(atom), -Indices:list(integer))
%!      is det.
%
%   Per particle, the 0-based position in Atoms of Template at the first
%   solution of Goal whose Template is one of Atoms, or -1 where there is
%   none: which of a few constants a particle answers, as numbers (the
%   Python bridge reads which occluder hides an object in each particle
%   this way, without a value per particle converted in between).
%
%   @error type_error(list(atom), Atoms) if Atoms is not a list of atoms.
filter_indices(F, Template, Goal, Atoms, Indices) :-
    must_be(list(atom), Atoms),
    filter_values(F, I, (Goal, nth0(I, Atoms, Template)), Values),
    maplist(index_value, Values, Indices).

index_value(V, I) :-
    (   integer(V) -> I = V ; I = -1 ).

%!  filter_packed_indices(+Filter, ?Template, +Goal, +Atoms:list(atom), -Indices) is det.
%
%   filter_indices/5, with Indices, where the engine reads them straight
%   from its columns (the batched engine's engine_packed_indices/5 with
%   its column library), a blob of doubles as filter_packed_rows/6 gives
%   (NaN for -1); else the list of integers of filter_indices/5.
filter_packed_indices(F, Template, Goal, Atoms, Indices) :-
    outside_filter(F), !,
    filter_call(F, filter_packed_indices(F, Template, Goal, Atoms, Indices)).
filter_packed_indices(F, Template, Goal, Atoms, Indices) :-
    must_be(list(atom), Atoms),
    filter_handle(F, E, S),
    (   current_predicate(E:engine_packed_indices/5),
        E:engine_packed_indices(S, Template, Goal, Atoms, Packed)
    ->  Indices = Packed
    ;   filter_indices(F, Template, Goal, Atoms, Indices)
    ).

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
    (   ground(X)
    ->  true
    ;   format(atom(Msg), 'not ground: ~p', [X]),
        throw(error(instantiation_error, context(ddc_filter:filter_step/4, Msg)))
    ).

