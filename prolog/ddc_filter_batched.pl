/*  ddc_filter_batched.pl -- the batched engine behind the filter API.

    Part of the DDC engine (ddc.pl is the module users load).  A thin
    adapter: implements the engine interface of the filter API
    (ddc_filter.pl, "Engines") over ddc_batch.pl's exports, which
    evaluate each clause once for a batch of particles.
*/

:- module(ddc_filter_batched,
          [ batched_init/6              % !State, +Module, +Items, +N, +Seed, +Threads
          ]).

:- use_module(ddc_records).
:- use_module(ddc_body, [info_derived_timed/2, info_rvs_untimed/2, info_rvs_timed/2]).
:- use_module(ddc_batch).
:- use_module(ddc_batch_col, [col_backend/1]).

:- use_module(ddc_ops).

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
    ;   throw(error(ddc(nothing_to_undo, query), _))
    ).

engine_resample(State, Is) :-
    batched_current(State, S0),
    batch_resample(S0, Is, S),
    commit(State, S0, S).

engine_holds(State, Goal, Flags) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_holds(S, G, Flags).

engine_values(State, Template, Goal, Values) :-
    batched_current(State, S),
    batch_query_goal(S, Goal, G),
    batch_values(S, Template, G, Values).

%   (No rows read straight from the batch: the filter API makes them from
%   the values.)
engine_rows(_, _, _, _, _) :-
    fail.

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
