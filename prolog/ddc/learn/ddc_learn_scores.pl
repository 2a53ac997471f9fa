/*  ddc_learn_scores.pl -- scoring a DC program on learning data: the
    log-likelihood, accuracy or RMSE of each target's groundings.
*/

:- module(ddc_learn_scores,
          [ learn_program_scores/5      % +Data, +ProgramFile, +Targets, +Options, -Scores
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(option)).
:- use_module('../lang/ddc_dist').
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_text, [term_text/3]).
:- use_module(ddc_learn_worlds, [world_alternatives/6]).
:- use_module(ddc_learn_nodes, [target_examples/4, target_value_goal/6]).

:- set_prolog_flag(optimise, true).

/** <module> Scores of a DC program on learning data

The program's clauses are read into the data module: a random variable's
clauses as '$prog_clause'(Name/KeyArity, Keys-Dist-Where, Body), its
derived predicates and Prolog clauses as clauses of the module (those the
data define already are left alone).  Each grounding of a target is then
scored by the first clause whose body holds, in each partial world its
proof needs (ddc_learn_worlds.pl).
*/

                 /*******************************
                 *       PROGRAM EVALUATION     *
                 *******************************/

%!  learn_program_scores(+Data, +ProgramFile, +Targets:list, +Options, -Scores:list(dict)) is det.
%
%   Score a DC program on the data: for each target (the internal names,
%   or [] for every random variable the program defines that has facts in
%   the data), every grounding in the data is scored by the first clause
%   of the program whose body holds in the data's world (the other facts
%   are its evidence): the log density (or mass) of the fact's value, the
%   prediction (the most probable value, or the mean).  Uncertain facts
%   give weighted partial worlds (expected scores).  Scores: one dict per
%   target with target, n (groundings), weight, log_likelihood (sum),
%   mean_log_likelihood, uncovered (groundings no clause applied to),
%   accuracy (discrete targets) or rmse (continuous).  Options:
%   examples(true) adds examples, each example's [Weight, LogLikelihood]
%   in the order of the target's groundings.
%
%   @error ddc_learn(value_not_in_program(Key, Value, Values), File:Line)
learn_program_scores(M, File, Targets0, Options, Scores) :-
    data_read_terms(File, own, Items),
    load_program(M, Items, Heads),
    (   Targets0 == []
    ->  findall(N, ( member(N/A, Heads), M:'$ddcl_pred'(N, A, rv(_)),
                     target_examples(M, N, A, Ks), Ks \== [] ), Targets),
        (   Targets == [] -> no_facts_error(M, File, Heads) ; true )
    ;   Targets = Targets0
    ),
    maplist(target_scores(M, File), Targets, Scores0),
    (   option(examples(true), Options)
    ->  Scores = Scores0
    ;   maplist([D0, D]>>del_dict(examples, D0, _, D), Scores0, Scores)
    ).

%   no_facts_error(+M, +Program, +Targets): none of the targets (N/A) has
%   a grounding in the test data; the error says how the test data were
%   read (their own declarations, the program's record, --bias files, or
%   none) and, without declarations, which file to pass.
no_facts_error(M, Program, Targets) :-
    (   M:'$ddcl_file'(Test, _) -> true ; Test = Program ),
    (   M:'$ddcl_bias_source'(Source) -> true ; Source = declared ),
    maplist(target_key_text(M), Targets, Names),
    atomic_list_concat(Names, ', ', Text),
    findall(N/A1, ( member(N/A, Targets), A1 is A+1, M:'$ddcl_pred'(N, A1, atom) ), Long),
    throw(error(ddc_learn(test_without_facts(Text, Program, Source, Long), Test:0), _)).

target_key_text(M, N/A, Text) :-
    length(As, A), K =.. [N|As], dc_term(M, K, DK), term_text(DK, [], Text).

load_program(M, Items0, Heads) :-
    maplist(internal_item(M), Items0, Items),
    dynamic(M:'$prog_clause'/3),
    retractall(M:'$prog_clause'(_, _, _)),
    forall(member(item(T, _, _, W), Items), program_item(M, T, W)),
    findall(N/A, M:'$prog_clause'(N/A, _, _), Hs0),
    sort(Hs0, Heads).

internal_item(M, item(T0, Vs, D, W), item(T, Vs, D, W)) :-
    internal_key(M, T0, T).

program_item(_, (:- _), _) :- !.
program_item(M, (K ~ D := B), W) :- !, program_rv(M, K, D, B, W).
program_item(M, (K ~ D <- B), W) :- !, program_rv(M, K, D, B, W).
program_item(M, (K ~ D), W) :- !, program_rv(M, K, D, true, W).
program_item(M, (H := B), W) :- !,
    (   callable(H), functor(H, N, A), \+ defined_in_data(M, N, A)
    ->  dc_goal(M, B, G, W), functor(H, HN, HA), dynamic(M:HN/HA), assertz(M:(H :- G))
    ;   true
    ).
program_item(M, C, _) :-
    ( C = (H :- _) -> true ; H = C ),
    (   callable(H), functor(H, N, A), \+ defined_in_data(M, N, A),
        \+ predicate_property(system:H, defined)
    ->  dynamic(M:N/A), assertz(M:C)
    ;   true
    ).

defined_in_data(M, N, A) :-
    functor(H, N, A),
    (   predicate_property(M:H, number_of_clauses(C)), C > 0 -> true
    ;   M:'$ddcl_background'(H0, _, _), \+ H0 \= H
    ).

program_rv(M, K, D, B, W) :-
    (   callable(K) -> true ; throw(error(ddc_learn(not_callable(K), W), _)) ),
    K =.. [N|Ks], length(Ks, A),
    dc_goal(M, B, G, W),
    assertz(M:'$prog_clause'(N/A, Ks-D-W, G)).

target_scores(M, File, N, _{target: Text, predicate: N, n: NE, weight: SW, log_likelihood: LL,
                           mean_log_likelihood: MLL, uncovered: U, accuracy: Acc, rmse: RMSE,
                           examples: PerExample}) :-
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   M:'$prog_clause'(N/A0, _, _) -> no_facts_error(M, File, [N/A0])
    ;   no_facts_error(M, File, [N/0])
    ),
    length(Vs, A), K0 =.. [N|Vs], dc_term(M, K0, T0), term_text(T0, [], Text),
    target_examples(M, N, A, Keys),
    length(Keys, NE),
    target_value_goal(M, N, A, Ks, Y, ValueGoal),
    Goal = ( ValueGoal,
             ( M:'$prog_clause'(N/A, Ks-D0-CW, G), once(M:G)
             ->  ddc_learn_facts:eval_dist_at(D0, CW, D), R = d(D)
             ;   R = uncovered
             ) ),
    foldl(score_example(M, N, Ks, Goal, Y-R, Spec), Keys, score_sums(0, 0, 0, 0, 0)-PerExample,
          S-[]),
    S = score_sums(SW, SLL, SC, SE, U),
    (   SW > 0, U =:= 0 -> MLL is SLL / SW ; SW > 0 -> MLL = -inf ; MLL = nan ),
    LL = SLL,
    (   Spec = discrete(_)
    ->  ( SW > 0 -> Acc is SC / SW ; Acc = nan ), RMSE = nan
    ;   Acc = nan, ( SW > 0 -> RMSE is sqrt(SE / SW) ; RMSE = nan )
    ).

%   score_example(..., +Key, +Sums0-[[Weight, LogLik]|Es], -Sums-Es): an
%   example's scores added to the sums, and its own weight and
%   log-likelihood (over its partial worlds) listed.
score_example(M, N, Ks, Goal, Out, Spec, Key, S0-[[W1, L1]|Es], S-Es) :-
    copy_term(Ks-Goal-Out, Key-G-O),
    empty_assoc(E0),
    K =.. [N|Key], example_weight(M, K, W),
    world_alternatives(M, G, O, E0, W, Alts),
    foldl(score_alternative(M, N, Key, Spec), Alts, S0, S),
    S0 = score_sums(Wa, La, _, _, _),
    S = score_sums(Wb, Lb, _, _, _),
    W1 is Wb - Wa,
    (   La =:= Lb -> L1 = 0.0 ; L1 is Lb - La ).

%   score_sums(Weight, LogLikelihood, Correct, SquaredError, Uncovered):
%   the sums over a target's groundings and partial worlds.
score_alternative(M, N, Key, Spec, alternative(Y-R, _, F, _),
                  score_sums(W0, L0, C0, E0, U0), score_sums(W, L, C, E, U)) :-
    W is W0 + F,
    (   R = d(D)
    ->  K =.. [N|Key],
        check_program_value(M, K, Y, D),
        dist_log_density(D, Y, LP),
        (   LP =:= -inf -> L is -inf ; L is L0 + F*LP ),
        (   Spec = discrete(_)
        ->  ( predicted(D, P), same_value(P, Y) -> C is C0 + F ; C = C0 ), E = E0
        ;   dist_mean(D, Mu), E is E0 + F*(Mu - Y)**2, C = C0
        ),
        U = U0
    ;   L = L0, C = C0, E = E0, U is U0 + 1
    ).

check_program_value(M, Key, Y, D) :-
    (   dist_support(D, Ps)
    ->  (   member(_-V, Ps), same_value(V, Y) -> true
        ;   dist_discrete(D), D = finite(PVs), \+ memberchk(_:Y, PVs)
        ->  findall(V, member(_:V, PVs), Vs),
            dc_term(M, Key, DK),
            ( fact_where(M, Key, W) -> true ; W = data ),
            throw(error(ddc_learn(value_not_in_program(DK, Y, Vs), W), _))
        ;   true
        )
    ;   true
    ).

predicted(D, V) :-
    dist_support(D, Ps),
    foldl([P-X, P0-X0, B]>>( P > P0 -> B = P-X ; B = P0-X0 ), Ps, -1-none, _-V).

same_value(A, B) :- number(A), number(B), !, A =:= B.
same_value(A, B) :- A == B.
