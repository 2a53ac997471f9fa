/*  ddc_learn_bias.pl -- the declarative bias of learning data (types,
    values, modes, targets, ranks, weights) and the kind of each predicate.
*/

:- module(ddc_learn_bias,
          [ bias_items/2,               % +Data, +Items
            bias_term/2,                % +Dialect, +Term
            finish_preds/2,             % +Data, +Items
            given_weight/3              % +Data, +Key, -Weight
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(error)).

:- use_module('../lang/ddc_ops').
:- op(700, xfx, ::).

/** <module> Declarative bias of learning data

The bias is read first, from every file (bias_items/2), so that facts can
be checked against it wherever they stand: the project's own type/1,
rv/1,2, threshold/2, learn/1, examples/2, mode/2,3, rank/1, weight/2 and
DreaML's base/1, thres/4, randomVariableNames/1, learn/4, mode/3,
rank/1 (docs/learning.md).  finish_preds/2 then decides for each
predicate whether it is a random variable or an atom, and writes the
modes' literals in the internal form.  Declarations are asserted in the
data module ('$ddcl_type'/5, '$ddcl_pred'/3, '$ddcl_mode'/6, ...).
*/

                 /*******************************
                 *        DECLARATIVE BIAS      *
                 *******************************/

%   Bias declarations are read first (from every file), so that facts can
%   be checked against them wherever they stand.

%!  bias_items(+Data, +Items:list) is det.
%
%   Assert the bias declarations among Items (item(Term, VarNames,
%   Dialect, File:Line)) in the data module, ranks last.
%
%   @error ddc_learn(Cause, File:Line) for a bad declaration.
bias_items(M, Items) :-
    forall(( member(item(T, Vs, D, W), Items), bias_term(D, T) ),
           bias_item(M, D, T, Vs, W)),
    rank_levels(M, Items).

%!  bias_term(+Dialect, +Term) is semidet.
%
%   Term is a declaration of the bias in Dialect (own or dreaml), not
%   data.
bias_term(dreaml, T) :- functor(T, N, A), memberchk(N/A, [base/1, thres/4, randomVariableNames/1,
                                                          mode/3, learn/4, rank/1]).
bias_term(own, T) :- functor(T, N, A), memberchk(N/A, [type/1, rv/2, rv/1, mode/2, mode/3,
                                                       threshold/2, learn/1, examples/2,
                                                       rank/1, weight/2]).

% -- DreaML's declarations
bias_item(M, dreaml, base(P), _, W) :- !,
    must_be_callable(P, W),
    P =.. [N|Types],
    assertz(M:'$ddcl_base'(N, Types, W)).
bias_item(M, dreaml, thres(N, Pos, Type, Dom), _, W) :- !,
    assertz(M:'$ddcl_dreaml'(N, thres(Pos, Type, Dom), W)).
bias_item(M, dreaml, randomVariableNames(Ns), _, W) :- !,
    must_be(list(atom), Ns),
    forall(member(N, Ns), assertz(M:'$ddcl_dreaml'(N, random, W))).
bias_item(M, dreaml, learn(N, A, Pos, Type), _, W) :- !,
    (   Pos =:= A -> true
    ;   throw(error(ddc_learn(value_not_last(N/A, Pos), W), _))
    ),
    KA is A-1,
    (   M:'$ddcl_target'(N, KA, _, _)
    ->  assertz(M:'$ddcl_warning'(W-duplicate_target(N)))
    ;   assertz(M:'$ddcl_target'(N, KA, dreaml(Type), W))
    ).
bias_item(M, dreaml, mode(T, Agg, L), _, W) :- !,
    add_mode(M, T, Agg, L, W).
% -- the project's own
bias_item(M, own, type(P), _, W) :- !,
    must_be_callable(P, W),
    P =.. [N|Types],
    length(Types, A),
    (   M:'$ddcl_type'(N, A, Types0, _, _), Types0 \== Types
    ->  throw(error(ddc_learn(declared_twice(N/A), W), _))
    ;   assertz(M:'$ddcl_type'(N, A, Types, none, W))
    ).
bias_item(M, own, rv(P), _, W) :- !,
    bias_item(M, own, rv(P, infer), [], W).
bias_item(M, own, rv(P, Spec0), _, W) :- !,
    must_be_callable(P, W),
    functor(P, N, A),
    (   value_spec(Spec0, Spec) -> true
    ;   throw(error(ddc_learn(bad_value_spec(Spec0), W), _))
    ),
    (   M:'$ddcl_pred'(N, A, K0), K0 \== rv(Spec)
    ->  throw(error(ddc_learn(declared_twice(N/A), W), _))
    ;   assertz(M:'$ddcl_pred'(N, A, rv(Spec)))
    ).
bias_item(M, own, threshold(P, Ts), _, W) :- !,
    must_be_callable(P, W),
    functor(P, N, A),
    (   is_list(Ts), Ts \== [], maplist(number, Ts), msort(Ts, Ts), sort(Ts, Ts)
    ->  assertz(M:'$ddcl_thresholds'(N/A, Ts))
    ;   throw(error(ddc_learn(bad_thresholds(Ts), W), _))
    ).
bias_item(M, own, learn(H), Vs, W) :- !,
    target_template(H, W, N, A, Args),
    var_names_of(Args, Vs, Names),
    (   M:'$ddcl_target'(N, A, _, _)
    ->  assertz(M:'$ddcl_warning'(W-duplicate_target(N)))
    ;   assertz(M:'$ddcl_target'(N, A, own(Names), W))
    ).
bias_item(M, own, examples(H, G), _, W) :- !,
    target_template(H, W, N, A, _),
    assertz(M:'$ddcl_examples'(N/A, H, G, W)).
bias_item(M, own, mode(T, L), _, W) :- !,
    add_mode(M, T, none, L, W).
bias_item(M, own, mode(T, Agg, L), _, W) :- !,
    add_mode(M, T, Agg, L, W).
bias_item(M, own, weight(K, W), _, W0) :- !,
    (   ground(K), callable(K), number(W), W > 0
    ->  (   given_weight(M, K, X)
        ->  throw(error(ddc_learn(weighted_twice(K, X, W), W0), _))
        ;   weight_fact(K, W, _, F), assertz(M:F)
        )
    ;   throw(error(ddc_learn(bad_weight(weight(K, W)), W0), _))
    ).
bias_item(_, _, rank(_), _, _) :- !.       % rank_levels/2, once all files are read

%!  given_weight(+Data, +Key, -Weight:number) is semidet.
%
%   The weight a weight(Key, W) item of the data gave the grounding Key.
given_weight(M, K, W) :-
    weight_fact(K, W, WN/WA, F),
    current_predicate(M:WN/WA),
    M:F.

%   weight_fact(+Key, ?Weight, -PI, -Fact): the clause of the data module
%   that holds Key's weight ('$weight:N'(K1, ..., Weight) for N(K1, ...)).
weight_fact(K, W, WN/WA, F) :-
    K =.. [N|Ks], atom_concat('$weight:', N, WN),
    append(Ks, [W], As), F =.. [WN|As],
    length(As, WA).

must_be_callable(P, W) :-
    (   callable(P) -> true ; throw(error(ddc_learn(not_callable(P), W), _)) ).

value_spec(infer, infer).
value_spec(discrete(L), D) :- is_list(L), L \== [], ground(L), sort(L, S),
    length(L, N), length(S, N), !, domain_spec(L, D).
value_spec(boolean, discrete([true, false])).
value_spec(continuous, continuous).
value_spec(count, count).

%   domain_spec(+Values, -Spec): discrete(Values) in the declared order; two
%   values true and false are the Boolean discrete([true, false]) (the
%   probability of true first, as the paper's finite(P1:true, P2:false)).
domain_spec(Vs, discrete([true, false])) :- msort(Vs, [false, true]), !.
domain_spec(Vs, discrete(Vs)).

%   target_template(+H, +Where, -Name, -KeyArity, -Args): a target written as
%   a template (occluder(A, O), renamed from occluder(A, O):t+1), Name/Arity,
%   or a name.
target_template(H, W, N, A, Args) :-
    (   H = N0/A0, atom(N0), integer(A0) -> N = N0, A = A0, length(Args, A)
    ;   atom(H) -> N = H, A = 0, Args = []
    ;   compound(H) -> H =.. [N|Args], length(Args, A)
    ;   throw(error(ddc_learn(not_callable(H), W), _))
    ).

var_names_of(Args, Vs, Names) :-
    maplist(var_name(Vs), Args, Names).

var_name(Vs, A, Name) :-
    (   var(A), member(Name0=V, Vs), V == A, \+ sub_atom(Name0, 0, _, _, '_')
    ->  Name = Name0
    ;   Name = '_'
    ).

%   add_mode(+M, +Target, +Agg, +Lit, +Where): '$ddcl_mode'(Id, N/A, Agg,
%   Cond, Lit, Where) with the aggregate in the project's names.  Literal
%   arguments are still in the file's form (finish_preds/2 adds the value
%   argument of a random variable in the own dialect).
add_mode(M, T, Agg0, L, W) :-
    (   atom(T) -> TN = T, TA = any
    ;   target_template(T, W, TN, TA, _)
    ),
    (   aggregate_name(Agg0, Agg) -> true
    ;   throw(error(ddc_learn(unknown_aggregate(Agg0), W), _))
    ),
    (   nonvar(L), L = (C, Lit) -> Cond = C
    ;   Cond = none, Lit = L
    ),
    (   callable(Lit), ( Cond == none ; callable(Cond) ) -> true
    ;   throw(error(ddc_learn(bad_mode_literal(L), W), _))
    ),
    aggregate_all(count, M:'$ddcl_mode'(_, _, _, _, _, _), Id0),
    Id is Id0+1,
    assertz(M:'$ddcl_mode'(Id, TN/TA, Agg, Cond, Lit, W)).

aggregate_name(none, none).
aggregate_name(cnt, count).
aggregate_name(count, count).
aggregate_name(avg, mean).
aggregate_name(mean, mean).
aggregate_name(max, max).
aggregate_name(min, min).
aggregate_name(maxMod, mode).
aggregate_name(mode, mode).
aggregate_name(minMod, antimode).
aggregate_name(antimode, antimode).

%   rank([p, q, [r, s], ...]): predicates of rank 1, 2, 3 (a list: the same
%   rank).  A predicate listed twice makes the order cyclic.
rank_levels(M, Items) :-
    forall(member(item(rank(L), _, D, W), Items), ( bias_term(D, rank(L)) -> rank_list(M, L, W) ; true )).

rank_list(M, L, W) :-
    (   is_list(L) -> true ; throw(error(ddc_learn(bad_rank(L), W), _)) ),
    forall(nth1(R, L, E),
           ( ( is_list(E) -> Es = E ; Es = [E] ),
             forall(member(P0, Es),
                    ( rank_name(P0, M, W, P),
                      (   M:'$ddcl_rank'(P, _)
                      ->  throw(error(ddc_learn(cyclic_rank(P), W), _))
                      ;   assertz(M:'$ddcl_rank'(P, R))
                      ) )) )).

rank_name(P0, _, _, P) :- atom(P0), !, P = P0.
rank_name(P0, _, _, P) :- compound(P0), P0 = N/_, atom(N), !, P = N.
rank_name(P0, _, _, P) :- compound(P0), !, functor(P0, P, _).
rank_name(P0, _, W, _) :- throw(error(ddc_learn(bad_rank(P0), W), _)).

                 /*******************************
                 *          PREDICATES          *
                 *******************************/

%!  finish_preds(+Data, +Items:list) is det.
%
%   Decide for each predicate whether it is a random variable (internal
%   arity: key arity + 1, the value last) or an atom, from the
%   declarations and, in the own dialect, from how the data are written
%   (K ~= V: a random variable); the argument types; and the modes in the
%   internal form.
finish_preds(M, Items) :-
    dreaml_preds(M),
    forall(( M:'$ddcl_examples'(N/A, _, _, _), \+ M:'$ddcl_pred'(N, A, _) ),
           assertz(M:'$ddcl_pred'(N, A, rv(discrete([true, false]))))),
    forall(member(item(T, _, own, W), Items), own_pred_kind(M, T, W)),
    forall(( M:'$ddcl_target'(N, A, own(_), _), \+ M:'$ddcl_pred'(N, A, _) ),
           assertz(M:'$ddcl_pred'(N, A, rv(discrete([true, false]))))),
    forall(( M:'$ddcl_type'(N, A, _, _, _), \+ M:'$ddcl_pred'(N, A, _) ),
           assertz(M:'$ddcl_pred'(N, A, atom))),
    forall(M:'$ddcl_pred'(N, A, K), declare_pred(M, N, A, K)),
    normalise_modes(M).

%   DreaML: randomVariableNames/1 and thres/4 make p(K1..Kn, V) a random
%   variable p(K1..Kn); base/1 gives the types (the last one the value's).
dreaml_preds(M) :-
    forall(M:'$ddcl_base'(N, Types, W),
           (   M:'$ddcl_dreaml'(N, random, _)
           ->  append(KTs, [VT], Types), length(KTs, A),
               dreaml_spec(M, N, A, Spec),
               assertz(M:'$ddcl_type'(N, A, KTs, VT, W)),
               assertz(M:'$ddcl_pred'(N, A, rv(Spec)))
           ;   length(Types, A),
               assertz(M:'$ddcl_type'(N, A, Types, none, W))
           )),
    forall(( M:'$ddcl_dreaml'(N, random, W), \+ M:'$ddcl_base'(N, _, _) ),
           throw(error(ddc_learn(no_base_declaration(N), W), _))).

dreaml_spec(M, N, A, Spec) :-
    A0 is A+1,
    (   M:'$ddcl_dreaml'(N, thres(Pos, Type, Dom), W)
    ->  (   Pos =:= A0 -> true
        ;   throw(error(ddc_learn(value_not_last(N/A0, Pos), W), _))
        ),
        (   Type == discrete, is_list(Dom), Dom \== [] -> domain_spec(Dom, Spec)
        ;   Type == continuous, Dom == [] -> Spec = infer_numeric
        ;   Type == continuous, Dom = ['-'|_]
        ->  Spec = continuous,
            exclude([X]>>memberchk(X, ['-', '+']), Dom, Ts),
            assertz(M:'$ddcl_thresholds'(N/A, Ts))
        ;   throw(error(ddc_learn(bad_value_spec(thres(N, Pos, Type, Dom)), W), _))
        )
    ;   Spec = infer
    ).

own_pred_kind(M, T, W) :-
    (   own_rv_head(T, K) -> Kind = rv(infer)
    ;   own_atom_head(T, K) -> Kind = atom
    ;   fail
    ),
    !,
    (   callable(K) -> true ; throw(error(ddc_learn(not_callable(K), W), _)) ),
    functor(K, N, A),
    (   M:'$ddcl_pred'(N, A, _) -> true ; assertz(M:'$ddcl_pred'(N, A, Kind)) ).
own_pred_kind(_, _, _).

own_rv_head(K ~= _, K).
own_rv_head(K ~ _, K).
own_rv_head((K ~ _ := _), K).
own_rv_head((K ~ _ <- _), K).

own_atom_head(_ :: A, A).
own_atom_head((H := _), H).
own_atom_head((H <- _), H).
own_atom_head((H :- _), H).
own_atom_head(A, A) :- callable(A), \+ A = (:- _), \+ A = (_ pr _).

declare_pred(M, N, A, rv(_)) :- !, A1 is A+1, dynamic(M:N/A1).
declare_pred(M, N, A, atom) :- dynamic(M:N/A).

%   normalise_modes(+M): the literals of the modes in the internal form:
%   p(+, -, V) for a random variable (the own dialect leaves the value out:
%   V is - for an attribute, true for a Boolean relation).
normalise_modes(M) :-
    findall(mode(Id, T, Agg, C0, L0, W), retract(M:'$ddcl_mode'(Id, T, Agg, C0, L0, W)), Ms),
    forall(member(mode(Id, T, Agg, C0, L0, W), Ms),
           ( W = F:_, M:'$ddcl_file'(F, D),
             mode_literal(M, D, C0, W, C), mode_literal(M, D, L0, W, L),
             assertz(M:'$ddcl_mode'(Id, T, Agg, C, L, W)) )).

mode_literal(_, _, none, _, none) :- !.
mode_literal(M, D, (A, B), W, (LA, LB)) :- !,
    mode_literal(M, D, A, W, LA), mode_literal(M, D, B, W, LB).
mode_literal(M, own, L0, W, L) :- !,
    functor(L0, N, A),
    (   M:'$ddcl_pred'(N, A, rv(Spec))
    ->  L0 =.. [N|As], ( Spec == discrete([true, false]) -> V = true ; V = (-) ),
        append(As, [V], As1), L =.. [N|As1]
    ;   M:'$ddcl_pred'(N, A, atom) -> L = L0
    ;   throw(error(ddc_learn(unknown_mode_predicate(N/A), W), _))
    ).
mode_literal(M, dreaml, L, W, L) :-
    functor(L, N, A),
    (   A1 is A-1, M:'$ddcl_pred'(N, A1, rv(_)) -> true
    ;   M:'$ddcl_pred'(N, A, atom) -> true
    ;   throw(error(ddc_learn(unknown_mode_predicate(N/A), W), _))
    ).
