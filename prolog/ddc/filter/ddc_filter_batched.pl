/** <module> The batched engine behind the filter API

Part of the DDC engine (ddc.pl is the module users load).  A thin
adapter: implements the engine interface of the filter API
(ddc_filter.pl, "Engines") over ddc_batch.pl's exports, which
evaluate each clause once for a batch of particles.
*/

:- module(ddc_filter_batched,
          [ batched_init/6              % !State, +Module, +Items, +N, +Seed, +Threads
          ]).

:- use_module(library(apply)).
:- use_module('../lang/ddc_records').
:- use_module('../lang/ddc_body', [info_derived_timed/2, info_rvs_untimed/2, info_rvs_timed/2]).
:- use_module('../batch/ddc_batch').
:- use_module('../batch/ddc_batch_col', [col_backend/1]).
:- use_module('../batch/ddc_batch_state').
:- use_module('../batch/ddc_batch_tables').

:- use_module('../lang/ddc_ops').

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%   A batched filter's state, held by the filter and updated in place: the
%   batch state (ddc_batch.pl, kept by batch_keep/2) and the previous one
%   for one undo (none if there is none).
:- record_type batched(current, previous).

%!  batched_init(!State, +Module, +Items, +N, +Seed, +Threads) is det.
%
%   State, a record batched(none, none) held by the filter, gets the
%   batch of N particles of the program in Module (Items: its
%   ddc_programs:program_items/2).
batched_init(State, M, Items, N, Seed, K) :-
    batch_new(M, Items, N, Seed, K, BS),
    batch_keep(BS, Kept),
    nb_link_batched_current(State, Kept).

%   commit(!State, +S0, +S): S is the current batch state, S0 the previous.
commit(State, S0, S) :-
    batch_keep(S, Kept),
    nb_link_batched_previous(State, S0),
    nb_link_batched_current(State, Kept).

engine_step(State, Weighted, Facts, LogWs) :-
    batched_current(State, S0),
    batch_step(S0, Weighted, Facts, step(S, LogWs)),
    commit(State, S0, S).

engine_undo(State) :-
    batched_previous(State, S0),
    (   S0 \== none
    ->  nb_link_batched_current(State, S0),
        nb_set_batched_previous(State, none)
    ).

engine_resample(State, Is) :-
    batched_current(State, S0),
    batch_resample(S0, Is, S),
    commit(State, S0, S).

%   engine_rename(!State, +Moves, +Is): the constants renamed by Moves in
%   the particles Is (1-based, sorted; filter_rename/3): a new current
%   state (the previous one, for undo, is kept) whose groups holding a
%   particle of Is have both tables renamed (ddc_batch_tables.pl,
%   rename_table/5; a pending older table is resampled first), the other
%   groups as they were.
engine_rename(State, Moves, Is) :-
    batched_current(State, S0),
    (   S0 = groups(Gs0)
    ->  foldl(renamed_group(Moves, Is), Gs0, Gs, 0, _),
        S = groups(Gs)
    ;   renamed_group(Moves, Is, S0, S, 0, _)
    ),
    batch_keep(S, Kept),
    nb_link_batched_current(State, Kept).

%   renamed_group(+Moves, +Is, +G0, -G, +Offset0, -Offset): group G0, whose
%   particles follow the first Offset0 of the filter, renamed in those of
%   Is.
renamed_group(Moves, Is, G0, G, Off0, Off) :-
    batch_size(G0, N),
    Off is Off0+N,
    findall(L, ( member(I, Is), I > Off0, I =< Off, L is I-Off0 ), Ls),
    (   Ls == []
    ->  G = G0
    ;   batch_state_module(G0, M), batch_state_time(G0, T),
        batch_state_facts(G0, Facts), batch_state_random(G0, R),
        batch_state_tables(G0, Tables0),
        tables_older_time(Tables0, T0), tables_older(Tables0, Older0),
        tables_latest_time(Tables0, T1), tables_latest(Tables0, Latest0),
        (   Older0 == none -> Older1 = none ; real_table(Older0, Older1) ),
        rename_table(Older1, Moves, Ls, N, Older),
        rename_table(Latest0, Moves, Ls, N, Latest),
        make_tables([older_time(T0), older(Older), latest_time(T1), latest(Latest)], Tables),
        make_batch_state([module(M), size(N), time(T), tables(Tables), facts(Facts),
                          random(R)], G)
    ).

engine_holds(State, Goal, Flags) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_holds(S, G, Flags).

engine_values(State, Template, Goal, Values) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_values(S, Template, G, Values).

%   (A variable's values read straight from its columns where it can,
%   ddc_batch:batch_rows/5; else the filter API makes the rows from the
%   values.)
engine_rows(State, Template, Goal, Width, Floats) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_rows(S, Template, G, Width, Floats).

%   engine_packed_rows(+State, +Template, +Goal, -Width, -Rows) is semidet:
%   engine_rows/5 with the floats in a blob of doubles
%   (ddc_filter:filter_packed_rows/6).
engine_packed_rows(State, Template, Goal, Width, Rows) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_packed_rows(S, Template, G, Width, Rows).

%   engine_packed_indices(+State, ?Template, +Goal, +Atoms, -Indices) is
%   semidet: ddc_filter:filter_packed_indices/5 read from the columns.
engine_packed_indices(State, Template, Goal, Atoms, Indices) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_packed_indices(S, Template, G, Atoms, Indices).

engine_time(State, T) :-
    batched_current(State, S),
    batch_time(S, T).

engine_size(State, N) :-
    batched_current(State, S),
    batch_size(S, N).

engine_statistics(State, [particles(N), time(T), engine(batched), columns(B)]) :-
    batched_current(State, S),
    batch_size(S, N),
    batch_time(S, T),
    col_backend(B).

engine_free(_).

%   batch_query_goal(+State, +Goal, -G): Goal with each untimed read or
%   derived atom that the program only defines with a time index read at
%   the current time t (as filter_holds/3 documents).
batch_query_goal(S, Goal, G) :-
    batch_module(S, M),
    M:'$ddc_info'(Info),
    info_derived_timed(Info, DerT),
    info_rvs_untimed(Info, RvU),
    info_rvs_timed(Info, RvT),
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
