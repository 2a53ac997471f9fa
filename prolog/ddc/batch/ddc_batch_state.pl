/*  ddc_batch_state.pl -- the state of a group of particles in the batched filter.

    Part of the batched particle filter (ddc_batch.pl, the API): the record
    that holds one group's particles (the whole filter's when it has one
    group), its copy kept across queries, the environment of a query on
    it, and the random stream a query draws from.
*/

:- module(ddc_batch_state,
          [ state_keep/2,               % +State, -Kept
            query_env/3,                % +State, -Env, -All
            with_state/2                % +State, :Goal
          ]).

:- use_module('../lang/ddc_records').
:- use_module(ddc_batch_tables).
:- use_module(ddc_batch_col, [ps_all/2]).
:- use_module(ddc_batch_eval).
:- use_module('../runtime/ddc_pool', [with_random_stream/3]).

:- set_prolog_flag(optimise, true).

/** <module> A group's state in the batched filter

A group's state is a batch_state/6 record:

    batch_state(Module, Size, Time, Tables, Facts, Random)

Module the module the program is compiled into, Size the number of
particles, Time the latest time T, Tables a tables/4 record
(ddc_batch_tables.pl) of the columns of times T-1 and T, Facts the facts
of time T, Random the state of the group's random generator.  A state is
never changed by a step or a resampling (they make a new one), so the
caller keeps the previous state for undo and for errors; a query draws
what it needs into the state's columns and advances its random stream in
place.
*/

%   batch_state(Module, Size, Time, Tables, Facts, Random): above.
:- record_type batch_state(module, size, time, tables, facts, random).

%   groups(States): a filter of groups (ddc_batch.pl, "Groups"), its
%   groups' states in the order of their particles.
:- record_type groups(states).

:- meta_predicate with_state(+, 0).

%!  state_keep(+State, -Kept) is det.
%
%   Kept is State's record and its tables/4 record assembled anew by
%   non-backtrackable assignment (nb_setarg/3, nb_linkarg/3), sharing
%   State's tables, facts and stream (ddc_batch:batch_keep/2).
state_keep(S, Kept) :-
    batch_state_tables(S, Tables),
    tables_older_time(Tables, T0), tables_older(Tables, Tab0),
    tables_latest_time(Tables, T1), tables_latest(Tables, Tab1),
    new_tables(KeptTables),
    nb_set_tables_older_time(KeptTables, T0),
    nb_link_tables_older(KeptTables, Tab0),
    nb_set_tables_latest_time(KeptTables, T1),
    nb_link_tables_latest(KeptTables, Tab1),
    batch_state_module(S, M), batch_state_size(S, N), batch_state_time(S, T),
    batch_state_facts(S, Facts), batch_state_random(S, R),
    new_batch_state(Kept),
    nb_set_batch_state_module(Kept, M),
    nb_set_batch_state_size(Kept, N),
    nb_set_batch_state_time(Kept, T),
    nb_link_batch_state_tables(Kept, KeptTables),
    nb_link_batch_state_facts(Kept, Facts),
    nb_link_batch_state_random(Kept, R).

%!  query_env(+State, -Env, -All:list(integer)) is det.
%
%   Env: the environment of a query at State's time (no observations,
%   no particles checked for overlaps); All: the particles 1..Size.
query_env(S, E, All) :-
    batch_state_module(S, M), batch_state_size(S, N), batch_state_time(S, T),
    batch_state_tables(S, Tables), batch_state_facts(S, Facts),
    fact_index(Facts, FactIndex),
    make_env([module(M), size(N), now(T), tables(Tables), facts(FactIndex), observations([]),
              checked([])], E),
    ps_all(N, All).

%!  with_state(+State, :Goal) is semidet.
%
%   Goal (a query) draws what it needs from State's random stream, which
%   goes on from there (in place: State is the filter's own term).
with_state(S, Goal) :-
    forget_collected,
    batch_state_random(S, R0),
    with_random_stream(state(R0), Goal, R1),
    nb_set_batch_state_random(S, R1).
