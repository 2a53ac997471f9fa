/*  ddc_learn_facts.pl -- the items of learning data other than its bias:
    facts, uncertain facts, background clauses, directives; the value of
    an uncertain fact in a partial world.
*/

:- module(ddc_learn_facts,
          [ load_item/2,                % +Data, +Item
            prob_table/2,               % +Name, -TableName
            fact_where/3,               % +Data, +Key, -Where
            pick/3,                     % +Key, +Dist, -Value
            dist_points/3               % +Dist, +Samples, -Points
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(error)).
:- use_module('../lang/ddc_dist').
:- use_module('../../ddc.pl', []).          % ddc:eval_dist/2: a distribution's parameters evaluated
:- use_module(ddc_learn_syntax, [dc_goal/4]).
:- use_module(ddc_learn_bias, [bias_term/2]).

:- use_module('../lang/ddc_ops').
:- op(700, xfx, ::).

/** <module> Facts and background clauses of learning data

A fact K ~= V is the clause K(.., V) of the data module, checked against
the bias; an uncertain one ('$prob:N'(K1..Kn, Dist)) makes its predicate
ask the partial world being proved (pick/3); a DC clause of the
background knowledge is compiled to '$bg:N'(K1..Kn, Dist, Where) :- Body.
*/

                 /*******************************
                 *             ITEMS            *
                 *******************************/

%!  load_item(+Data, +Item) is det.
%
%   Assert a data item (item(Term, VarNames, Dialect, File:Line)) that is
%   not a bias declaration: a fact, an uncertain fact, a background clause
%   or a directive.
%
%   @error ddc_learn(Cause, File:Line) for a bad item.
load_item(_, item(T, _, D, _)) :- bias_term(D, T), !.
load_item(M, item((:- Dir), _, _, W)) :- !,
    directive(M, Dir, W).
load_item(M, item(T, Vs, own, W)) :- !,
    own_item(M, T, Vs, W).
load_item(M, item(T, Vs, dreaml, W)) :-
    dreaml_item(M, T, Vs, W).

directive(M, use_module(library(L)), _) :- !, M:use_module(library(L)).
directive(_, use_module(_), _) :- !.
directive(_, use_module(_, _), _) :- !.
directive(_, ensure_loaded(_), _) :- !.
directive(_, discontiguous(_), _) :- !.
directive(_, dynamic(_), _) :- !.
directive(_, set_prolog_flag(_, _), _) :- !.
directive(_, first_applicable(_), _) :- !.
directive(_, initialization(_), _) :- !.
directive(_, op(_, _, _), _) :- !.          % applied while reading (lang/ddc_source.pl)
directive(_, D, W) :-
    throw(error(ddc_learn(bad_directive(D), W), _)).

% -- the own dialect
own_item(M, K ~= V, _, W) :- !,
    (   ground(K), ground(V), callable(K)
    ->  rv_fact(M, K, V, W)
    ;   throw(error(ddc_learn(non_ground_fact(K ~= V), W), _))
    ).
own_item(M, (K ~ D := B), _, W) :- !, background_rv(M, K, D, B, W).
own_item(M, (K ~ D <- B), _, W) :- !, background_rv(M, K, D, B, W).
own_item(M, K ~ D0, _, W) :- !,
    ddc:dist_sugar(D0, D),                  % the engine's shorthand: uniform(A, B), finite(P:V, ...)
    (   ground(K), callable(K), ground(D), D = val(V)
    ->  rv_fact(M, K, V, W)
    ;   ground(K), callable(K), ground(D)
    ->  prob_fact(M, K, D, W)
    ;   background_rv(M, K, D, true, W)
    ).
own_item(M, P :: A, _, W) :- !,
    (   ground(A), callable(A), number(P), P >= 0, P =< 1
    ->  prob_atom(M, A, P, W)
    ;   throw(error(ddc_learn(bad_probabilistic_fact(P :: A), W), _))
    ).
own_item(M, (H := B), _, W) :- !, own_derived(M, H, B, W).
own_item(M, (H <- B), _, W) :- !, own_derived(M, H, B, W).
own_item(M, (H :- B), _, W) :- !, prolog_background(M, (H :- B), W).
own_item(M, T pr _, Vs, W) :- !, own_item(M, T, Vs, W).
own_item(M, A, _, W) :-
    callable(A),
    (   ground(A) -> atom_fact(M, A, W) ; prolog_background(M, A, W) ).

own_derived(M, H, B, W) :-
    (   B == true, ground(H), callable(H)
    ->  atom_fact(M, H, W)
    ;   callable(H)
    ->  dc_goal(M, B, G, W),
        assert_background(M, (H :- G), W),
        assertz(M:'$ddcl_background'(H, (H := B), W))
    ;   throw(error(ddc_learn(not_callable(H), W), _))
    ).

% -- DreaML's dialect: plain Prolog facts and clauses, random variables
%    with their value last
dreaml_item(M, (H :- B), _, W) :- !,
    prolog_background(M, (H :- B), W).
dreaml_item(M, F, _, W) :-
    callable(F),
    functor(F, N, A),
    (   A > 0, A1 is A-1, M:'$ddcl_pred'(N, A1, rv(_)), ground(F)
    ->  F =.. [N|As], append(Ks, [V], As), K =.. [N|Ks],
        rv_fact(M, K, V, W)
    ;   ground(F), M:'$ddcl_pred'(N, A, rv(S)), \+ M:'$ddcl_pred'(N, A, atom),
        memberchk(S, [infer, infer_numeric, discrete([true, false])])
    ->  rv_fact(M, F, true, W)              % DreaML's held-out files: hasLoan(a, l) for
                                            % hasLoan(a, l, true), as its loader reads them
    ;   ground(F)
    ->  atom_fact(M, F, W)
    ;   prolog_background(M, F, W)
    ).

%   rv_fact(+M, +Key, +Value, +Where)
rv_fact(M, K, V, W) :-
    functor(K, N, A),
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   M:'$ddcl_pred'(N, A, atom)
    ->  throw(error(ddc_learn(atom_with_value(N/A), W), _))
    ;   Spec = infer, assertz(M:'$ddcl_pred'(N, A, rv(infer)))
    ),
    check_value(Spec, K, V, M, W),
    K =.. [N|Ks], append(Ks, [V0], As), F =.. [N|As],
    (   clause(M:F, true)
    ->  (   V0 == V
        ->  repeated_fact(M, N, A, W)
        ;   throw(error(ddc_learn(key_defined_twice(K, V0, V), W), _))
        )
    ;   M:'$ddcl_prob_pred'(N, A),
        prob_table(N, PN), append(Ks, [_], PAs), PF =.. [PN|PAs], clause(M:PF, true)
    ->  throw(error(ddc_learn(key_defined_twice(K, other), W), _))
    ;   V0 = V,
        assertz(M:F),
        fact_line(M, N, Ks, W)
    ).

%   fact_line(+M, +N, +Keys, +Where): '$line:N'(K1..Kn, File:Line), for
%   errors about a fact found later (a test value the learned program does
%   not know).
fact_line(M, N, Ks, W) :-
    atom_concat('$line:', N, LN),
    append(Ks, [W], As), LF =.. [LN|As],
    assertz(M:LF).

%!  fact_where(+Data, +Key, -Where) is semidet.
%
%   The File:Line of the fact that gave Key its value.
fact_where(M, K, W) :-
    K =.. [N|Ks],
    atom_concat('$line:', N, LN),
    length(Ks, A), A1 is A+1,
    current_predicate(M:LN/A1),
    append(Ks, [W0], As), LF =.. [LN|As],
    once(M:LF), W = W0.

%   repeated_fact(+M, +N, +A, +Where): the same fact once more (FinancialData.pl
%   repeats each district's facts in every fold): read once, and one warning
%   per predicate says how often.
repeated_fact(M, N, A, W) :-
    (   retract(M:'$ddcl_warning'(W0-repeated_facts(N/A, C0)))
    ->  C is C0+1, assertz(M:'$ddcl_warning'(W0-repeated_facts(N/A, C)))
    ;   assertz(M:'$ddcl_warning'(W-repeated_facts(N/A, 1)))
    ).

%   check_value(+Spec, +Key, +Value, +M, +Where)
check_value(discrete(D), K, V, M, W) :- !,
    (   memberchk(V, D) -> true
    ;   number(V), \+ maplist(number, D)
    ->  throw(error(ddc_learn(continuous_declared_discrete(K, V, D), W), _))
    ;   functor(K, N, A), declaration_where(M, N, A, DW),
        throw(error(ddc_learn(value_not_in_domain(K, V, D, DW), W), _))
    ).
check_value(continuous, K, V, _, W) :- !,
    (   number(V) -> true
    ;   throw(error(ddc_learn(not_a_number(K, V), W), _))
    ).
check_value(count, K, V, _, W) :- !,
    (   integer(V), V >= 0 -> true
    ;   throw(error(ddc_learn(not_a_count(K, V), W), _))
    ).
check_value(infer_numeric, K, V, _, W) :- !,        % DreaML's continuous: a number, or
    (   ( number(V) ; V == true ; V == false ) -> true   % true/false for a relation
    ;   throw(error(ddc_learn(not_a_number(K, V), W), _))
    ).
check_value(_, _, _, _, _).                          % inferred at the end (infer_specs/1)

declaration_where(M, N, A, W) :-
    (   M:'$ddcl_dreaml'(N, thres(_, _, _), W) -> true
    ;   M:'$ddcl_type'(N, A, _, _, W) -> true
    ;   M:'$ddcl_target'(N, A, _, W) -> true
    ;   W = unknown
    ).

%   prob_fact(+M, +Key, +Dist, +Where): a random variable whose value is
%   uncertain.  '$prob:N'(K1,...,Kn, Dist) holds the distribution; the
%   variable's predicate gets one clause that asks the partial world.
prob_fact(M, K, D, W) :-
    catch(dist_check(D), E, bad_dist(E, D, W)),
    functor(K, N, A),
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   Spec = infer, assertz(M:'$ddcl_pred'(N, A, rv(infer)))
    ),
    (   dist_discrete(D)
    ->  dist_support(D, Pairs),
        forall(member(_-V, Pairs), check_value(Spec, K, V, M, W))
    ;   Spec == continuous -> true
    ;   Spec == infer -> true
    ;   throw(error(ddc_learn(continuous_distribution_for(K, Spec), W), _))
    ),
    K =.. [N|Ks], append(Ks, [_], As), F =.. [N|As],
    (   clause(M:F, true) -> throw(error(ddc_learn(key_defined_twice(K, other), W), _)) ; true ),
    prob_table(N, PN),
    append(Ks, [D], PAs), PF =.. [PN|PAs],
    assertz(M:PF),
    fact_line(M, N, Ks, W),
    prob_clause(M, N, A, rv).

prob_atom(M, A0, P, W) :-
    functor(A0, N, Ar),
    (   M:'$ddcl_pred'(N, Ar, rv(_))
    ->  prob_fact(M, A0, bool(P), W)
    ;   ( M:'$ddcl_pred'(N, Ar, atom) -> true ; assertz(M:'$ddcl_pred'(N, Ar, atom)) ),
        A0 =.. [N|Ks],
        prob_table(N, PN), append(Ks, [bool(P)], PAs), PF =.. [PN|PAs],
        (   clause(M:A0, true) -> throw(error(ddc_learn(key_defined_twice(A0, other), W), _)) ; true ),
        assertz(M:PF),
        prob_clause(M, N, Ar, atom)
    ).

%!  prob_table(+Name:atom, -TableName:atom) is det.
%
%   The predicate that holds the distributions of Name's uncertain facts.
prob_table(N, PN) :- atom_concat('$prob:', N, PN).

%   prob_clause(+M, +N, +A, +Kind): once per predicate,
%     N(K1..Kn, V) :- '$prob:N'(K1..Kn, D), ddc_learn_facts:pick(N(K1..Kn), D, V).
%   (an atom: pick(..., true)).
prob_clause(M, N, A, _) :- M:'$ddcl_prob_pred'(N, A), !.
prob_clause(M, N, A, Kind) :-
    length(Ks, A), K =.. [N|Ks],
    prob_table(N, PN), append(Ks, [D], PAs), PG =.. [PN|PAs],
    (   Kind == rv -> append(Ks, [V], As), H =.. [N|As]
    ;   H = K, V = true
    ),
    functor(H, HN, HA), dynamic(M:HN/HA),
    assertz(M:(H :- PG, ddc_learn_facts:pick(K, D, V))),
    assertz(M:'$ddcl_prob_pred'(N, A)).

atom_fact(M, A0, W) :-
    functor(A0, N, Ar),
    (   M:'$ddcl_pred'(N, Ar, rv(Spec))
    ->  (   memberchk(Spec, [discrete([true, false]), infer, infer_numeric])
        ->  rv_fact(M, A0, true, W)
        ;   throw(error(ddc_learn(atom_for_random_variable(N/Ar), W), _))
        )
    ;   ( M:'$ddcl_pred'(N, Ar, atom) -> true ; assertz(M:'$ddcl_pred'(N, Ar, atom)) ),
        (   clause(M:A0, true) -> repeated_fact(M, N, Ar, W)
        ;   assertz(M:A0)
        )
    ).

bad_dist(error(E, _), D, W) :- !,
    throw(error(ddc_learn(bad_distribution(D, E), W), _)).
bad_dist(E, _, _) :- throw(E).

%   background_rv(+M, +Key, +Dist, +Body, +Where): a DC clause of the
%   background knowledge.  Compiled to '$bg:N'(K1..Kn, Dist) :- Goal; the
%   variable's predicate asks the first clause that applies (DC's
%   semantics) and takes its value: val(V) is V, any other distribution
%   is a choice of the partial world (pick/3).
background_rv(M, K, D, B, W) :-
    (   callable(K) -> true ; throw(error(ddc_learn(not_callable(K), W), _)) ),
    functor(K, N, A),
    (   M:'$ddcl_pred'(N, A, rv(_)) -> true
    ;   M:'$ddcl_pred'(N, A, atom) -> throw(error(ddc_learn(atom_with_value(N/A), W), _))
    ;   assertz(M:'$ddcl_pred'(N, A, rv(infer)))
    ),
    dc_goal(M, B, G, W),
    K =.. [N|Ks],
    atom_concat('$bg:', N, BN),
    append(Ks, [D1, W], BAs), BH =.. [BN|BAs],
    assert_background(M, (BH :- G, ddc_learn_facts:eval_dist_at(D, W, D1)), W),
    assertz(M:'$ddcl_background'(K, (K ~ D := B), W)),
    (   M:'$ddcl_bg_rv'(N, A) -> true
    ;   assertz(M:'$ddcl_bg_rv'(N, A)),
        length(Vs, A), VK =.. [N|Vs], append(Vs, [V], HAs), H =.. [N|HAs],
        append(Vs, [Dist, Where], CAs), C =.. [BN|CAs],
        functor(H, HN, HA), dynamic(M:HN/HA),
        assertz(M:(H :- ( ground(VK) -> once(C) ; C ),
                       ddc_learn_facts:dist_value(VK, Dist, Where, V)))
    ).

%   eval_dist_at(+D0, +Where, -D): the distribution with its parameters
%   evaluated (gaussian(X+1, 0.5) -> gaussian(2.3, 0.5)), checked.
eval_dist_at(D0, W, D) :-
    catch(( ddc:dist_sugar(D0, D1), ddc:eval_dist(D1, D), ( D = val(_) -> true ; dist_check(D) ) ),
          E, bad_dist(E, D0, W)).

%   dist_value(+Key, +Dist, +Where, -V)
dist_value(_, val(V0), _, V) :- !, V = V0.
dist_value(K, D, _, V) :- pick(K, D, V).

prolog_background(M, C, W) :-
    assert_background(M, C, W),
    clause_head_of(C, H),
    assertz(M:'$ddcl_background'(H, C, W)).

clause_head_of((H :- _), H) :- !.
clause_head_of(H, H).

assert_background(M, C, W) :-
    clause_head_of(C, H),
    (   callable(H) -> true ; throw(error(ddc_learn(not_callable(H), W), _)) ),
    functor(H, N, A),
    (   predicate_property(system:H, defined)
    ->  throw(error(ddc_learn(redefines_builtin(N/A), W), _))
    ;   true
    ),
    dynamic(M:N/A),
    assertz(M:C).

                 /*******************************
                 *        PARTIAL WORLDS        *
                 *******************************/

%!  pick(+Key, +Dist, -Value) is semidet.
%
%   The value of an uncertain random variable in the partial world being
%   proved (the assoc in the global variable ddcl_assign).  A key the world
%   has not assigned yet throws ddcl_need(Key, Dist): the caller
%   (world_alternatives/6 in ddc_learn_worlds.pl) splits the world on it
%   and proves again.
pick(K, D, V) :-
    nb_setval(ddcl_touched, true),
    (   nb_current(ddcl_assign, A), A \== [] -> true ; empty_assoc(A) ),
    (   get_assoc(K, A, V0)
    ->  V = V0
    ;   throw(ddcl_need(K, D))
    ).

%!  dist_points(+Dist, +Samples:integer, -Points:list(pair)) is det.
%
%   The values a partial world may give a variable with distribution Dist,
%   as Prob-Value pairs: the support of a discrete distribution, exactly;
%   Samples draws of a continuous one, each of weight 1/Samples, from
%   SWI-Prolog's random generator (set_random(seed(S)) repeats them).
dist_points(D, S, Ps) :-
    (   dist_support(D, Ps0) -> Ps = Ps0
    ;   must_be(positive_integer, S),
        W is 1/S,
        findall(W-V, ( between(1, S, _), dist_sample(D, V) ), Ps)
    ).
