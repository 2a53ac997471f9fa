/*  ddc_learn_outcomes.pl -- what a candidate literal says of each row of a
    node: its branch and value, in each partial world the proof needs.
*/

:- module(ddc_learn_outcomes,
          [ learn_evaluate/4,           % +Data, +Node, +CandidateIds, -Outcomes
            learn_evaluate_rows/5,      % +Data, +Node, +CandidateId, +Rows, -Outcome
            node_outcomes/6,            % +Data, +IndexedRows, ?Bind, +Goal, ?Out, -Results
            outcome_goal/5              % +Data, +Spec, -Bind, -Goal, -Out
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module('../lang/ddc_models').                % the aggregates' mean_list/2, mode_list/2, ...
:- use_module(ddc_learn_records).
:- use_module(ddc_learn_worlds, [world_alternatives/6, in_world/2]).
:- use_module(ddc_learn_candidates, [agg_call/4, candidate_id/3, fresh_values/2]).

:- set_prolog_flag(optimise, true).

/** <module> Outcomes of candidate literals

A candidate's outcome in a row is outcome(Branch, X, FreshValues): the
branch the row takes, the value X (a regressor of the leaf's model, NaN
where none) and the values of the variables the literal introduces.  Each
candidate's goal is compiled once into the data module (outcome_goal/5);
a row whose proof reads an uncertain fact its world has not assigned is
proved again in each partial world that assigns it (ddc_learn_worlds.pl).
*/

                 /*******************************
                 *   OUTCOMES IN PARTIAL WORLDS *
                 *******************************/

%!  learn_evaluate(+Data, +Node, +CandidateIds:list, -Outcomes:list(dict)) is det.
%
%   For each candidate, its outcome in each row of Node: a dict of lists
%   row (the node's row index, from 0), branch, factor (the probability of
%   the partial world in which the outcome holds, relative to the row's),
%   x (the value, NaN where none), pure (false where the proof read an
%   uncertain fact: the outcome may differ in another world).  A row
%   appears once per partial world it splits into.
learn_evaluate(M, Node, Ids, Outs) :-
    M:'$ddcl_node'(Node, _, Rows),
    maplist(evaluate_rows(M, Rows), Ids, Outs).

%!  learn_evaluate_rows(+Data, +Node, +CandidateId, +RowIndices, -Outcome:dict) is det.
%
%   learn_evaluate/4 for some rows of Node only (those whose outcome at the
%   root was not pure).
learn_evaluate_rows(M, Node, Id, Is, Out) :-
    M:'$ddcl_node'(Node, _, Rows),
    findall(I-R, ( member(I, Is), nth0(I, Rows, R) ), IRs),
    evaluate_indexed(M, IRs, Id, Out).

evaluate_rows(M, Rows, Id, Out) :-
    length(Rows, N), N1 is N-1,
    ( N1 >= 0 -> numlist(0, N1, Is) ; Is = [] ),
    pairs_keys_values(IRs, Is, Rows),
    evaluate_indexed(M, IRs, Id, Out).

evaluate_indexed(M, IRs, Id, _{row: Rs, branch: Bs, factor: Fs, x: Xs, pure: Ps}) :-
    M:'$ddcl_cand'(Id, _, Spec),
    outcome_goal(M, Spec, Bind, Goal, Out),
    node_outcomes(M, IRs, Bind, Goal, Out, Results),
    outcome_lists(Results, Rs, Bs, Fs, Xs, Ps).

outcome_lists([], [], [], [], [], []).
outcome_lists([row_result(I, _, _, F, P, outcome(B, X, _))|T],
              [I|Is], [B|Bs], [F|Fs], [X|Xs], [P|Ps]) :-
    outcome_lists(T, Is, Bs, Fs, Xs, Ps).

%!  node_outcomes(+Data, +IndexedRows:list(pair), ?Bind, +Goal, ?Out,
%!                -Results:list) is det.
%
%   The outcome of Goal (from outcome_goal/5) in each row I-row(Bindings,
%   World) and partial world, row_result(I, Bindings, World, Factor, Pure,
%   Out) in row order.  A row whose proof reads no uncertain fact the
%   row's world has not assigned is proved once, in a failure-driven loop
%   (no copy of the goal); only the others (unproved_row(I, Bindings,
%   World)) split their worlds (world_alternatives/6).
node_outcomes(M, IRs, Bind, Goal, Out, Results) :-
    findall(R, ( member(I-row(Bs, W), IRs), row_outcome(Bind, Goal, Out, I, Bs, W, R) ), Rs),
    foldl(world_outcomes(M, Bind, Goal, Out), Rs, Results, []).

row_outcome(Bind, Goal, Out, I, Bs, W, R) :-
    nb_setval(ddcl_touched, false),
    Bind = Bs,
    catch(( in_world(W, Goal) -> R0 = ok ; R0 = failed ), ddcl_need(_, _), R0 = need),
    (   R0 == ok
    ->  nb_getval(ddcl_touched, T),
        ( T == true -> P = false ; P = true ),
        R = row_result(I, Bs, W, 1.0, P, Out)
    ;   R0 == need
    ->  R = unproved_row(I, Bs, W)
    ;   throw(error(ddc_learn(goal_failed(Goal), data), _))
    ).

world_outcomes(_, _, _, _, R, [R|T], T) :- R = row_result(_, _, _, _, _, _), !.
world_outcomes(M, Bind, Goal, Out, unproved_row(I, Bs, W), L, T) :-
    copy_term(Bind-Goal-Out, Bs-G-O),
    world_alternatives(M, G, O, W, 1.0, Alts),
    foldl(alternative_result(I, Bs), Alts, L, T).

alternative_result(I, Bs, alternative(O, W, F, P), [row_result(I, Bs, W, F, P, O)|T], T).

%!  outcome_goal(+Data, +Spec, -Bind, -Goal, -Out) is det.
%
%   Goal, once Bind (the node variables' values) is bound, always succeeds
%   with Out = outcome(Branch, X, FreshValues).
%   The goal is compiled once per candidate, as the clause
%   '$ddcl_out'(Id, Bind, Out) :- Goal of the data module, so that each row
%   runs compiled code instead of a meta-call of the whole conjunction.
outcome_goal(M, Spec, Bind, M:'$ddcl_out'(Id, Bind, Out), Out) :-
    candidate_id(M, Spec, Id),
    (   M:'$ddcl_out_done'(Id) -> true
    ;   copy_term(Spec, Copy),
        candidate_kind(Copy, Kind),
        candidate_goal(Copy, G),
        candidate_inputs(Copy, Ins),
        candidate_fresh(Copy, Fresh),
        candidate_value(Copy, Val),
        candidate_domain(Copy, Dom),
        candidate_thresholds(Copy, Ts),
        candidate_aggregate(Copy, Agg),
        bind_goal(Ins, BindList, BG),
        fresh_values(Fresh, FVs),
        kind_goal(Kind, Agg, M:G, Val, Dom, Ts, B, X, KG),
        optimised_assert(M, ('$ddcl_out'(Id, BindList, outcome(B, X, FVs)) :- BG, KG)),
        assertz(M:'$ddcl_out_done'(Id))
    ).

optimised_assert(M, Clause) :-
    current_prolog_flag(optimise, Old),
    setup_call_cleanup(set_prolog_flag(optimise, true), assertz(M:Clause),
                       set_prolog_flag(optimise, Old)).

%   bind_goal(+Ins, ?Bindings, -Goal): unify each template variable with
%   its node variable's value in the row.
bind_goal([], _, true).
bind_goal([P-V|Ins], Bs, ( nth0(P, Bs, V), G )) :- bind_goal(Ins, Bs, G).

kind_goal(discrete, _, G, V, Dom, _, B, X, Goal) :-
    length(Dom, K),
    Goal = ( once(G) -> ddc_learn_outcomes:domain_index(V, Dom, B), X = nan ; B = K, X = nan ).
kind_goal(numeric, _, G, V, _, _, B, X, Goal) :-
    Goal = ( once(G) -> ddc_learn_outcomes:numeric_value(V, X), B = 0 ; B = 1, X = nan ).
kind_goal(threshold, _, G, V, _, Ts, B, X, Goal) :-
    length(Ts, K), K1 is K+1,
    Goal = ( once(G) -> ddc_learn_outcomes:numeric_value(V, X0),
                        ddc_learn_outcomes:threshold_bin(X0, Ts, 0, B), X = nan
           ; B = K1, X = nan ).
kind_goal(test, _, G, _, _, _, B, X, Goal) :-
    Goal = ( once(G) -> B = 0, X = nan ; B = 1, X = nan ).
kind_goal(count, _, G, _, _, _, B, X, Goal) :-
    Goal = ( findall(x, G, L), length(L, X), B = 0 ).
kind_goal(agg_numeric, Agg, G, V, _, _, B, X, Goal) :-
    agg_call(Agg, L, X, Call),                  % mean_list(L, X), ...
    Goal = ( findall(V, G, L),
             (   L == [] -> B = 1, X = nan
             ;   ddc_learn_outcomes:numeric_list(L), ddc_learn_outcomes:Call, B = 0
             ) ).
kind_goal(agg_discrete, Agg, G, V, Dom, _, B, X, Goal) :-
    length(Dom, K),
    agg_call(Agg, L, Mo, Call),                 % mode_list(L, Mo), ...
    Goal = ( findall(V, G, L),
             (   L == [] -> B = K, X = nan
             ;   ddc_learn_outcomes:Call, ddc_learn_outcomes:domain_index(Mo, Dom, B), X = nan
             ) ).

domain_index(V, Dom, B) :-
    (   nth0(B0, Dom, V0), V0 == V -> B = B0
    ;   throw(error(ddc_learn(value_not_in_domain(value, V, Dom, unknown), data), _))
    ).

numeric_value(V, X) :-
    (   number(V) -> X = V
    ;   throw(error(ddc_learn(not_a_number(value, V), data), _))
    ).

numeric_list(L) :-
    (   maplist(number, L) -> true
    ;   member(V, L), \+ number(V) -> throw(error(ddc_learn(not_a_number(value, V), data), _))
    ).

threshold_bin(X, [], B, B) :- !, number(X).
threshold_bin(X, [T|Ts], B0, B) :- ( X < T -> B = B0 ; B1 is B0+1, threshold_bin(X, Ts, B1, B) ).
