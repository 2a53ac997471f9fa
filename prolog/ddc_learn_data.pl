/*  ddc_learn_data.pl -- the learner's data: facts, background knowledge and
    declarative bias read from DC files into a module of their own.

    The structure learner (ddc_learn.pl) learns distributional clauses from
    relational data with discrete and continuous attributes.  This module
    reads that data, checks it against its declarative bias, and answers
    the questions the learner asks of it: which values a random variable
    has, which literals hold, in one partial possible world at a time.
*/

:- module(ddc_learn_data,
          [ learn_data_load/3,          % +Files, +Options, -Data
            learn_data_free/1,          % +Data
            learn_data_targets/2,       % +Data, -Targets
            learn_data_pred/4,          % +Data, ?Name, ?KeyArity, ?Kind
            example_weight/3,           % +Data, +Key, -Weight
            learn_data_warnings/2,      % +Data, -Warnings
            message_text/2,             % +Message, -Text
            dc_goal/4,                  % +Data, +DCGoal, -Goal, +Where
            internal_key/3,             % +Data, +DCKey, -Key
            dc_term/3,                  % +Data, +Internal, -DCTerm
            pick/3,                     % +Key, +Dist, -Value
            fact_where/3,               % +Data, +Key, -Where
            dist_points/3,              % +Dist, +Samples, -Points
            data_read_terms/3,          % +File, +Mode, -Items
            op(700, xfx, ~),
            op(700, xfx, ~=),
            op(1105, xfx, :=),
            op(1105, xfx, <-),
            op(1150, xfx, pr),
            op(700, xfx, ::)
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(error)).
:- use_module(library(option)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(ddc_dist).
:- use_module(ddc_models).
:- use_module(ddc, []).          % ddc:eval_dist/2: a distribution's parameters evaluated

:- op(700, xfx, ~).
:- op(700, xfx, ~=).
:- op(1105, xfx, :=).
:- op(1105, xfx, <-).
:- op(1150, xfx, pr).
:- op(700, xfx, ::).

/** <module> Learning data for the DC structure learner

A data set is one or more files.  Each holds, in any order, facts (the
training data), background knowledge and the declarative bias.  Two
dialects are read; a file that contains any of DreaML's declarations
(base/1, thres/4, randomVariableNames/1, learn/4) is read as DreaML's,
every other file as the project's own (docs/learning.md gives both in
full).

Facts (own dialect), as the paper writes them:

    pos(o1):t ~= 2.3.                 % a random variable's value
    occluded_by(o1, o2):t+1.          % an atom that holds
    colour(o1) ~= red.   on(a, b).    % static facts
    0.7 :: occluded_by(o3, o2):t+1.   % a probabilistic atom
    label(e1) ~ finite([0.7:a, 0.3:b]).   % a probabilistic value

Background knowledge: DC clauses (`h ~ D := Body`, `h := Body`) and plain
Prolog clauses.  Time-indexed terms p(X):t and p(X):t+1 are learned as the
static predicates p_t(X) and p_t1(X) (section 4 of the paper) and mapped
back when clauses are written.

Internally a random variable p(K1,...,Kn) with value V is the Prolog fact
p(K1,...,Kn,V) (DreaML's representation: the value last), an atom is
itself, in a module of its own per data set (the Data handle).  A
probabilistic fact makes that predicate consult the partial world being
proved: pick/3 returns the value the world assigned to the key, or throws
ddcl_need(Key, Dist) so that the caller splits the world on that key.

Errors are error(ddc_learn(Cause, File:Line), _), printed as
`File:Line: cause`.
*/

:- dynamic data_counter/1.
data_counter(0).

:- meta_predicate data_goal(+, 0).

                 /*******************************
                 *            LOADING           *
                 *******************************/

%!  learn_data_load(+Files:list, +Options:list, -Data:atom) is det.
%
%   Read the data files into a new module Data.  Options: targets(false)
%   reads data to score a program on (no target need be declared, none
%   need have facts).  Every fact is checked against the bias: a value outside a
%   declared domain, a non-number for a continuous attribute, a key with
%   two values, a mode that names an unknown predicate, a target without
%   facts, a rank that lists a predicate twice are errors naming the file
%   and line.
%
%   @error ddc_learn(Cause, File:Line)
learn_data_load(Files, Options, Data) :-
    must_be(list, Files),
    must_be(list, Options),
    (   Files == [] -> domain_error(non_empty_list, Files) ; true ),
    maplist(resolve_data_file, Files, Paths),
    new_data_module(Data),
    (   option(targets(false), Options) -> Check = false ; Check = true ),
    catch(load_into(Data, Paths, Check), E, ( learn_data_free(Data), throw(E) )).

resolve_data_file(Spec, Path) :-
    (   absolute_file_name(Spec, Path, [access(read), file_errors(fail)])
    ->  true
    ;   absolute_file_name(Spec, Path0, [extensions([pl]), access(read), file_errors(fail)])
    ->  Path = Path0
    ;   term_to_atom(Spec, A),
        throw(error(ddc_learn(no_such_file(A), A:0), _))
    ).

new_data_module(M) :-
    with_mutex(ddc_learn_data,
               ( retract(data_counter(N0)), N is N0+1, assertz(data_counter(N)) )),
    atom_concat('ddc_learn_data_', N, M),
    set_module(M:base(system)),
    set_module(M:class(temporary)),
    M:use_module(library(lists)),
    M:use_module(library(apply)),
    module_property(ddc_models, file(ModelsFile)),
    M:use_module(ModelsFile),
    maplist(declare_dynamic(M), ['$ddcl_pred'/3, '$ddcl_type'/5, '$ddcl_base'/3,
                                 '$ddcl_dreaml'/3, '$ddcl_timed'/3, '$ddcl_mode'/6,
                                 '$ddcl_thresholds'/2, '$ddcl_rank'/2, '$ddcl_target'/4,
                                 '$ddcl_examples'/4, '$ddcl_background'/3, '$ddcl_file'/2,
                                 '$ddcl_warning'/1, '$ddcl_prob_pred'/2, '$ddcl_bg_rv'/2]).

declare_dynamic(M, PI) :- dynamic(M:PI).

%!  learn_data_free(+Data:atom) is det.
%
%   Forget a data set (its module and everything learned about it).
learn_data_free(M) :-
    (   current_module(M), sub_atom(M, 0, _, _, ddc_learn_data_)
    ->  forall(( current_predicate(M:N/A), functor(H, N, A),
                 \+ predicate_property(M:H, imported_from(_)) ),
               abolish(M:N/A))
    ;   true
    ).

load_into(M, Paths, Check) :-
    maplist(read_file_items, Paths, ItemLists),
    append(ItemLists, Items0),
    maplist(dialect_of, Paths, ItemLists, Dialects),
    pairs_keys_values(FDs, Paths, Dialects),
    forall(member(F-D, FDs), assertz(M:'$ddcl_file'(F, D))),
    time_rename_items(M, Items0, Items),
    bias_items(M, Items),
    finish_preds(M, Items),
    forall(member(I, Items), load_item(M, I)),
    forall(( member(item(T, Vs, _, W), Items), M:'$ddcl_background'(_, _, W) ),
           assertz(M:'$ddcl_named'(W, T-Vs))),
    check_bias(M, Check).

%   Items: item(Term, VarNames, Dialect, File:Line).
read_file_items(Path, Items) :-
    data_read_terms(Path, own, Items0),
    dialect_of(Path, Items0, D),
    maplist(set_dialect(D), Items0, Items).

set_dialect(D, item(T, Vs, _, W), item(T, Vs, D, W)).

dialect_of(_, Items, dreaml) :-
    member(item(T, _, _, _), Items),
    ( T = base(_) ; T = thres(_, _, _, _) ; T = randomVariableNames(_) ; T = learn(_, _, _, _) ),
    !.
dialect_of(_, _, own).

%!  data_read_terms(+File, +Dialect, -Items) is det.
%
%   Items is item(Term, VariableNames, Dialect, File:Line) for each clause
%   of File, read with the DC operators (and `::`).
%
%   @error ddc_learn(syntax_error(Msg), File:Line)
data_read_terms(File, Dialect, Items) :-
    setup_call_cleanup(open(File, read, S),
                       read_items(S, File, Dialect, Items),
                       close(S)).

read_items(S, File, D, Items) :-
    catch(read_term(S, T, [ module(ddc_learn_data), term_position(P),
                            variable_names(Vs), syntax_errors(error) ]),
          E, read_error(E, File)),
    (   T == end_of_file
    ->  Items = []
    ;   stream_position_data(line_count, P, Line),
        Items = [item(T, Vs, D, File:Line)|Rest],
        read_items(S, File, D, Rest)
    ).

read_error(error(syntax_error(Msg), Ctx), File) :- !,
    (   Ctx = stream(_, Line, _, _) -> true
    ;   Ctx = file(_, Line, _, _) -> true
    ;   Line = 0
    ),
    throw(error(ddc_learn(syntax_error(Msg), File:Line), _)).
read_error(E, _) :-
    throw(E).

                 /*******************************
                 *             TIME             *
                 *******************************/

%   Time-indexed terms become static predicates: p(X):t -> p_t(X),
%   p(X):t+1 -> p_t1(X); '$ddcl_timed'(Internal, Base, t|t1) remembers the
%   mapping.  Anything else after a colon that is not a module qualifier
%   (p:t-1, p:0) is an error: learning data describe one step.
time_rename_items(M, Items0, Items) :-
    maplist(time_rename_item(M), Items0, Items).

time_rename_item(M, item(T0, Vs, D, W), item(T, Vs, D, W)) :-
    time_rename(T0, M, W, T).

time_rename(V, _, _, V) :- var(V), !.
time_rename(X:T, M, W, Y) :- T == t, callable(X), !,
    timed_name(X, t, M, W, Y).
time_rename(X:TE, M, W, Y) :- nonvar(TE), TE = T+1, T == t, callable(X), !,
    timed_name(X, t1, M, W, Y).
time_rename((X:T)+1, M, W, Y) :- T == t, callable(X), !,
    timed_name(X, t1, M, W, Y).
time_rename(X:TE, _, W, _) :-
    callable(X), time_like(TE), !,
    throw(error(ddc_learn(unsupported_time(X:TE), W), _)).
time_rename(T0, M, W, T) :-
    compound(T0), !,
    compound_name_arguments(T0, N, As0),
    maplist(time_rename_arg(M, W), As0, As),
    compound_name_arguments(T, N, As).
time_rename(T, _, _, T).

time_rename_arg(M, W, A0, A) :- time_rename(A0, M, W, A).

time_like(T) :- integer(T), !.
time_like(T) :- nonvar(T), ( T = A+B ; T = A-B ), A == t, integer(B).

timed_name(X, Time, M, W, Y) :-
    X =.. [N|Args],
    atomic_list_concat([N, '_', Time], IN),
    (   M:'$ddcl_timed'(IN, N0, T0), ( N0 \== N ; T0 \== Time )
    ->  throw(error(ddc_learn(time_name_clash(IN, N0:T0, N:Time), W), _))
    ;   M:'$ddcl_timed'(IN, _, _) -> true
    ;   assertz(M:'$ddcl_timed'(IN, N, Time))
    ),
    Y =.. [IN|Args].

                 /*******************************
                 *        DECLARATIVE BIAS      *
                 *******************************/

%   Bias declarations are read first (from every file), so that facts can
%   be checked against them wherever they stand.

bias_items(M, Items) :-
    forall(( member(item(T, Vs, D, W), Items), bias_term(D, T) ),
           bias_item(M, D, T, Vs, W)),
    rank_levels(M, Items).

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
    ->  K =.. [N|Ks], atom_concat('$weight:', N, WN),
        append(Ks, [X], WAs), WF =.. [WN|WAs],
        (   length(WAs, WA), current_predicate(M:WN/WA), M:WF
        ->  throw(error(ddc_learn(weighted_twice(K, X, W), W0), _))
        ;   append(Ks, [W], As), F =.. [WN|As], assertz(M:F)
        )
    ;   throw(error(ddc_learn(bad_weight(weight(K, W)), W0), _))
    ).
bias_item(_, _, rank(_), _, _) :- !.       % rank_levels/2, once all files are read

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

%   finish_preds(+M, +Items): decide for each predicate whether it is a
%   random variable (internal arity: key arity + 1, the value last) or an
%   atom, from the declarations and, in the own dialect, from how the data
%   are written (K ~= V: a random variable); the argument types; and the
%   modes in the internal form.
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


                 /*******************************
                 *             ITEMS            *
                 *******************************/

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

prob_table(N, PN) :- atom_concat('$prob:', N, PN).

%   prob_clause(+M, +N, +A, +Kind): once per predicate,
%     N(K1..Kn, V) :- '$prob:N'(K1..Kn, D), ddc_learn_data:pick(N(K1..Kn), D, V).
%   (an atom: pick(..., true)).
prob_clause(M, N, A, _) :- M:'$ddcl_prob_pred'(N, A), !.
prob_clause(M, N, A, Kind) :-
    length(Ks, A), K =.. [N|Ks],
    prob_table(N, PN), append(Ks, [D], PAs), PG =.. [PN|PAs],
    (   Kind == rv -> append(Ks, [V], As), H =.. [N|As]
    ;   H = K, V = true
    ),
    functor(H, HN, HA), dynamic(M:HN/HA),
    assertz(M:(H :- PG, ddc_learn_data:pick(K, D, V))),
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
    assert_background(M, (BH :- G, ddc_learn_data:eval_dist_at(D, W, D1)), W),
    assertz(M:'$ddcl_background'(K, (K ~ D := B), W)),
    (   M:'$ddcl_bg_rv'(N, A) -> true
    ;   assertz(M:'$ddcl_bg_rv'(N, A)),
        length(Vs, A), VK =.. [N|Vs], append(Vs, [V], HAs), H =.. [N|HAs],
        append(Vs, [Dist, Where], CAs), C =.. [BN|CAs],
        functor(H, HN, HA), dynamic(M:HN/HA),
        assertz(M:(H :- ( ground(VK) -> once(C) ; C ),
                       ddc_learn_data:dist_value(VK, Dist, Where, V)))
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
                 *        FINAL CHECKS          *
                 *******************************/

%   check_bias(+M): every predicate a mode names is known, every target
%   has facts, the values of undeclared random variables give their kind.
check_bias(M, false) :- !,
    infer_specs(M),
    materialise_derived(M).
check_bias(M, true) :-
    infer_specs(M),
    materialise_derived(M),
    forall(M:'$ddcl_mode'(_, _, _, C, L, W), ( mode_preds_known(M, C, W), mode_preds_known(M, L, W) )),
    forall(M:'$ddcl_target'(N, A, _, W), check_target(M, N, A, W)),
    forall(( M:'$ddcl_mode'(_, TN/_, _, _, _, W), TN \== any,
             \+ M:'$ddcl_target'(TN, _, _, _), \+ M:'$ddcl_pred'(TN, _, _) ),
           throw(error(ddc_learn(mode_for_unknown_target(TN), W), _))),
    (   M:'$ddcl_target'(_, _, _, _) -> true
    ;   M:'$ddcl_file'(F, _) -> throw(error(ddc_learn(no_targets, F:0), _))
    ).

infer_specs(M) :-
    forall(( M:'$ddcl_pred'(N, A, rv(S)), ( S == infer ; S == infer_numeric ) ),
           ( rv_values(M, N, A, Vs),
             inferred_spec(S, Vs, Spec),
             retract(M:'$ddcl_pred'(N, A, rv(S))),
             assertz(M:'$ddcl_pred'(N, A, rv(Spec))) )),
    forall(( M:'$ddcl_pred'(N, A, rv(discrete([true, false]))),
             M:'$ddcl_thresholds'(N/A, _) ),
           retractall(M:'$ddcl_thresholds'(N/A, _))).

%   rv_values(+M, +N, +A, -Values): the distinct values of N/A in the facts
%   (certain and uncertain ones).
rv_values(M, N, A, Vs) :-
    length(Ks, A), append(Ks, [V], As), F =.. [N|As],
    findall(V, clause(M:F, true), Vs1),
    prob_table(N, PN), append(Ks, [D], PAs), PF =.. [PN|PAs],
    findall(V2, ( M:'$ddcl_prob_pred'(N, A), clause(M:PF, true), dist_discrete(D),
                  dist_support(D, Ps), member(_-V2, Ps) ), Vs2),
    append(Vs1, Vs2, Vs0),
    sort(Vs0, Vs).

inferred_spec(_, [], any) :- !.
inferred_spec(_, Vs, continuous) :- maplist(number, Vs), !.
inferred_spec(_, Vs, discrete([true, false])) :- subtract(Vs, [false, true], []), !.
inferred_spec(infer, Vs, discrete(Vs)) :- maplist(atomic, Vs), !.
inferred_spec(_, _, any).

%   materialise_derived(+M): a derived atom of the background knowledge
%   that some mode reads (DreaML's districtClientAccount(D, C, A) :-
%   clientDistrict(C, D, true), hasAccount(C, A, true)) is replaced by its
%   solutions, when they do not depend on uncertain facts and number at
%   most 200,000: a call with only its last argument bound then takes an
%   index instead of a join over every client (measured on FinancialData.pl:
%   13.7 s -> 0.05 s for one candidate at the root of stdMonthW).  The
%   rules stay in '$ddcl_background'/3 for the learned program.
materialise_derived(M) :-
    findall(N/A, ( M:'$ddcl_mode'(_, _, _, C, L, _), member(Lit, [C, L]), Lit \== none,
                   conj_member(Lit, G), functor(G, N, A),
                   learn_data_pred(M, N, A, atom),
                   functor(H, N, A), M:'$ddcl_background'(H0, _, _), \+ H0 \= H ), Ps0),
    sort(Ps0, Ps),
    forall(member(P, Ps), ignore(materialise(M, P))).

conj_member((A, B), G) :- !, ( conj_member(A, G) ; conj_member(B, G) ).
conj_member(G, G).

materialise(M, N/A) :-
    Cap = 200000,
    Cap1 is Cap+1,
    functor(H, N, A),
    catch(( empty_assoc(E), b_setval(ddcl_assign, E),
            once(findnsols(Cap1, H, M:H, Hs)) ),
          _, fail),
    length(Hs, L), L =< Cap,
    sort(Hs, Facts),
    retractall(M:H),
    forall(member(F, Facts), assertz(M:F)).

mode_preds_known(_, none, _) :- !.
mode_preds_known(M, (A, B), W) :- !, mode_preds_known(M, A, W), mode_preds_known(M, B, W).
mode_preds_known(M, L, W) :-
    functor(L, N, Ar),
    (   A1 is Ar-1, M:'$ddcl_pred'(N, A1, rv(_)) -> true
    ;   M:'$ddcl_pred'(N, Ar, atom) -> true
    ;   functor(H, N, Ar), predicate_property(M:H, defined), \+ predicate_property(M:H, imported_from(_))
    ->  true
    ;   throw(error(ddc_learn(unknown_mode_predicate(N/Ar), W), _))
    ).

%   has_facts(+M, +N, +A): the random variable N/A has a certain or an
%   uncertain fact.
has_facts(M, N, A) :-
    length(Ks, A), append(Ks, [_], As), F =.. [N|As],
    (   clause(M:F, true) -> true
    ;   M:'$ddcl_prob_pred'(N, A)
    ), !.

check_target(M, N, A, W) :-
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   throw(error(ddc_learn(target_not_random(N/A), W), _))
    ),
    (   Spec == any -> throw(error(ddc_learn(target_without_values(N/A), W), _)) ; true ),
    (   M:'$ddcl_examples'(N/A, _, _, _) -> true
    ;   has_facts(M, N, A) -> true
    ;   throw(error(ddc_learn(target_without_facts(N/A), W), _))
    ),
    (   M:'$ddcl_target'(N, A, dreaml(Type), _)
    ->  (   Type == discrete, Spec = discrete(_) -> true
        ;   Type == continuous, ( Spec == continuous ; Spec == count ) -> true
        ;   throw(error(ddc_learn(target_type_mismatch(N/A, Type, Spec), W), _))
        )
    ;   true
    ).

                 /*******************************
                 *            QUERIES           *
                 *******************************/

%!  learn_data_targets(+Data, -Targets:list) is det.
%
%   Targets is a list of target(Name, KeyArity, Spec, VarNames, Where) in
%   the order of the files.
learn_data_targets(M, Targets) :-
    findall(target(N, A, Spec, Names, W),
            ( M:'$ddcl_target'(N, A, How, W), M:'$ddcl_pred'(N, A, rv(Spec)),
              ( How = own(Names) -> true ; length(Names, A), maplist(=('_'), Names) ) ),
            Targets).

%!  example_weight(+Data, +Key, -Weight) is det.
%
%   The weight of a grounding (weight(Key, W) in the data; 1 when none is
%   given): how many examples it stands for.
example_weight(M, K, W) :-
    K =.. [N|Ks], atom_concat('$weight:', N, WN),
    append(Ks, [W0], As), F =.. [WN|As],
    length(As, A),
    (   current_predicate(M:WN/A), M:F -> W = W0 ; W = 1.0 ).

%!  learn_data_pred(+Data, ?Name, ?KeyArity, ?Kind) is nondet.
%
%   Kind is rv(Spec) (Spec: discrete(Domain), continuous, count, any) or
%   atom.
learn_data_pred(M, N, A, K) :-
    M:'$ddcl_pred'(N, A, K).

%!  learn_data_warnings(+Data, -Warnings:list(string)) is det.
%
%   The data's warnings, each as a line `File:Line: cause`.
learn_data_warnings(M, Ws) :-
    findall(T, ( M:'$ddcl_warning'(W), message_text(ddc_learn_warning(W), T) ), Ws).

%!  message_text(+Message, -Text:string) is det.
%
%   A message term of this module rendered as print_message/2 would.
message_text(Msg, Text) :-
    (   phrase(prolog:message(Msg), Lines)
    ->  with_output_to(string(Text), print_message_lines(current_output, '', Lines))
    ;   term_string(Msg, Text)
    ).

                 /*******************************
                 *     DC BODIES AS GOALS       *
                 *******************************/

%!  internal_key(+Data, +DCKey, -Key) is det.
%
%   The internal form of a random variable or atom as written in a DC
%   program: occluded_by(A, O):t+1 -> occluded_by_t1(A, O).
internal_key(M, K0, K) :-
    time_rename(K0, M, internal, K).

%!  dc_term(+Data, +Internal, -DCTerm) is det.
%
%   The inverse of internal_key/3: occluded_by_t1(A, O) ->
%   occluded_by(A, O):t+1.
dc_term(M, K, T) :-
    callable(K),
    K =.. [N|As],
    (   M:'$ddcl_timed'(N, Base, Time)
    ->  K0 =.. [Base|As],
        ( Time == t -> T = K0:t ; T = K0:t+1 )
    ;   T = K
    ).

%!  dc_goal(+Data, +DCGoal, -Goal, +Where) is det.
%
%   Translate a DC body (time already renamed) into a Prolog goal over the
%   data module: `K ~= V` calls K's predicate with V appended, an atom of
%   a Boolean random variable means `~= true`, findall_forward/3 is
%   findall/3, a comparison with a random variable as an operand reads it
%   first.  true/1 and sample/2 (fresh randomness in a body) are not data.
%
%   @error ddc_learn(Cause, Where)
dc_goal(_, V, _, W) :- var(V), !,
    throw(error(ddc_learn(variable_goal, W), _)).
dc_goal(_, true, true, _) :- !.
dc_goal(M, (A, B), (GA, GB), W) :- !, dc_goal(M, A, GA, W), dc_goal(M, B, GB, W).
dc_goal(M, (A ; B), (GA ; GB), W) :- !, dc_goal(M, A, GA, W), dc_goal(M, B, GB, W).
dc_goal(M, (A -> B), (GA -> GB), W) :- !, dc_goal(M, A, GA, W), dc_goal(M, B, GB, W).
dc_goal(M, (A *-> B), (GA *-> GB), W) :- !, dc_goal(M, A, GA, W), dc_goal(M, B, GB, W).
dc_goal(M, \+ A, \+ GA, W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, once(A), once(GA), W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, ignore(A), ignore(GA), W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, forall(A, B), forall(GA, GB), W) :- !, dc_goal(M, A, GA, W), dc_goal(M, B, GB, W).
dc_goal(M, findall(T, A, L), findall(T, GA, L), W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, findall_forward(T, A, L), findall(T, GA, L), W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, aggregate_all(S, A, R), aggregate_all(S, GA, R), W) :- !, dc_goal(M, A, GA, W).
dc_goal(M, K ~= V, G, W) :- !,
    (   callable(K) -> true ; throw(error(ddc_learn(not_callable(K), W), _)) ),
    rv_call(M, K, V, G, W).
dc_goal(_, true(_), _, W) :- !, throw(error(ddc_learn(random_body(true/1), W), _)).
dc_goal(_, sample(_, _), _, W) :- !, throw(error(ddc_learn(random_body(sample/2), W), _)).
dc_goal(M, G0, G, W) :-
    compound(G0), functor(G0, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=]),
    G0 =.. [Op, A0, B0],
    ( rv_operand(M, A0) ; rv_operand(M, B0) ), !,
    operand(M, A0, A, GA, W), operand(M, B0, B, GB, W),
    G1 =.. [Op, A, B],
    G = (GA, GB, G1).
dc_goal(M, G0, G, W) :-
    callable(G0), !,
    functor(G0, N, A),
    (   M:'$ddcl_pred'(N, A, rv(discrete([true, false])))
    ->  rv_call(M, G0, true, G, W)
    ;   M:'$ddcl_pred'(N, A, rv(_))
    ->  throw(error(ddc_learn(random_variable_as_atom(N/A), W), _))
    ;   predicate_property(ddc_models:G0, exported)
    ->  G = ddc_models:G0
    ;   G = G0
    ).
dc_goal(_, G, _, W) :-
    throw(error(ddc_learn(not_callable(G), W), _)).

rv_call(M, K, V, G, _) :-
    K =.. [N|Ks],
    functor(K, N, A),
    (   M:'$ddcl_pred'(N, A, _) -> true
    ;   assertz(M:'$ddcl_pred'(N, A, rv(any)))
    ),
    append(Ks, [V], As),
    G =.. [N|As],
    A1 is A+1,
    (   current_predicate(M:N/A1) -> true ; dynamic(M:N/A1) ).

rv_operand(M, X) :-
    callable(X), \+ number(X), functor(X, N, A), M:'$ddcl_timed'(N, _, _),
    M:'$ddcl_pred'(N, A, rv(_)).

operand(M, X, V, G, W) :-
    (   rv_operand(M, X) -> rv_call(M, X, V, G, W) ; V = X, G = true ).

                 /*******************************
                 *        PARTIAL WORLDS        *
                 *******************************/

%!  pick(+Key, +Dist, -Value) is semidet.
%
%   The value of an uncertain random variable in the partial world being
%   proved (the assoc in the global variable ddcl_assign).  A key the world
%   has not assigned yet throws ddcl_need(Key, Dist): the caller
%   (ddc_learn:expand/5) splits the world on it and proves again.
pick(K, D, V) :-
    nb_setval(ddcl_touched, true),
    (   nb_current(ddcl_assign, A), A \== [] -> true ; empty_assoc(A) ),
    (   get_assoc(K, A, V0)
    ->  V = V0
    ;   throw(ddcl_need(K, D))
    ).

%   data_goal(+M, :Goal): Goal in the data module.
data_goal(_, G) :- call(G).

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

                 /*******************************
                 *            MESSAGES          *
                 *******************************/

:- multifile prolog:message//1.

prolog:message(error(ddc_learn(Cause, Where), _)) -->
    learn_where(Where),
    learn_cause(Cause).
prolog:message(ddc_learn_warning(Where-Cause)) -->
    learn_where(Where),
    learn_cause(Cause).

learn_where(File:Line) --> { integer(Line), Line > 0 }, !, [ '~w:~w: '-[File, Line] ].
learn_where(File:_) --> !, [ '~w: '-[File] ].
learn_where(W) --> [ '~w: '-[W] ].

learn_cause(syntax_error(Msg)) --> !, [ 'syntax error: ~w'-[Msg] ].
learn_cause(no_such_file(F)) --> !, [ 'no such file: ~w'-[F] ].
learn_cause(unsupported_time(T)) --> !,
    [ '~q: learning data describe one step: only :t and :t+1 are allowed'-[T] ].
learn_cause(time_name_clash(IN, A, B)) --> !,
    [ '~w would stand for both ~q and ~q'-[IN, A, B] ].
learn_cause(value_not_last(P, Pos)) --> !,
    [ '~w: the value must be the last argument (position ~w given)'-[P, Pos] ].
learn_cause(duplicate_target(N)) --> !, [ 'target ~w is declared twice; learned once'-[N] ].
learn_cause(bad_value_spec(S)) --> !,
    [ 'bad values ~q: expected discrete([V,...]), boolean, continuous or count'-[S] ].
learn_cause(declared_twice(P)) --> !, [ '~w is declared twice with other values'-[P] ].
learn_cause(bad_thresholds(T)) --> !, [ 'bad thresholds ~q: a sorted list of distinct numbers'-[T] ].
learn_cause(not_callable(T)) --> !, [ '~q is not a predicate term'-[T] ].
learn_cause(unknown_aggregate(A)) --> !,
    [ 'unknown aggregate ~q: none, count, mean, max, min, mode, antimode (or DreaML''s cnt, avg, maxMod, minMod)'-[A] ].
learn_cause(bad_mode_literal(L)) --> !, [ 'bad mode literal ~q'-[L] ].
learn_cause(bad_rank(R)) --> !, [ 'bad rank ~q: a list of predicate names'-[R] ].
learn_cause(cyclic_rank(P)) --> !,
    [ 'rank/1 lists ~w twice: the order of predicates would be cyclic'-[P] ].
learn_cause(no_base_declaration(N)) --> !,
    [ 'random variable ~w has no base/1 declaration (its argument types)'-[N] ].
learn_cause(unknown_mode_predicate(P)) --> !,
    [ 'mode names ~w, which has no facts, declaration or background clauses'-[P] ].
learn_cause(bad_directive(D)) --> !, [ 'unknown directive ~q'-[D] ].
learn_cause(non_ground_fact(F)) --> !, [ 'a fact must be ground: ~q'-[F] ].
learn_cause(bad_probabilistic_fact(F)) --> !,
    [ 'bad probabilistic fact ~q: P :: Atom with 0 =< P =< 1 and a ground atom'-[F] ].
learn_cause(atom_with_value(P)) --> !,
    [ '~w is an atom elsewhere in the data and has a value here'-[P] ].
learn_cause(key_defined_twice(K, V0, V)) --> !, [ '~q is given two values, ~q and ~q'-[K, V0, V] ].
learn_cause(key_defined_twice(K, other)) --> !, [ '~q is given twice (certain and uncertain)'-[K] ].
learn_cause(repeated_facts(P, N)) --> !,
    [ '~w: ~D facts repeat an earlier one exactly; each is read once'-[P, N] ].
learn_cause(continuous_declared_discrete(K, V, D)) --> !,
    [ '~q ~~= ~q: a number, but the attribute is declared discrete with values ~q (declare it continuous?)'-[K, V, D] ].
learn_cause(value_not_in_domain(K, V, D, DW)) --> !,
    [ '~q ~~= ~q: ~q is not among the declared values ~q'-[K, V, V, D] ],
    (   { DW = F:L } -> [ ' (~w:~w)'-[F, L] ] ; [] ).
learn_cause(not_a_number(K, V)) --> !,
    [ '~q ~~= ~q: not a number, but the attribute is declared continuous'-[K, V] ].
learn_cause(not_a_count(K, V)) --> !,
    [ '~q ~~= ~q: not a count (a non-negative integer)'-[K, V] ].
learn_cause(continuous_distribution_for(K, S)) --> !,
    [ '~q: a continuous distribution for a variable with values ~q'-[K, S] ].
learn_cause(atom_for_random_variable(P)) --> !,
    [ '~w is a random variable with values other than true/false; write K ~~= V'-[P] ].
learn_cause(bad_distribution(D, E)) --> !, [ 'bad distribution ~q: ~q'-[D, E] ].
learn_cause(redefines_builtin(P)) --> !, [ 'background clause redefines the built-in ~w'-[P] ].
learn_cause(mode_for_unknown_target(T)) --> !,
    [ 'mode for ~w, which is not a target (no learn/1 or learn/4) and has no facts'-[T] ].
learn_cause(no_targets) --> !, [ 'no target: declare one with learn/1 (or DreaML''s learn/4)'-[] ].
learn_cause(target_not_random(P)) --> !,
    [ 'target ~w is not a random variable (facts as atoms: declare rv(..., boolean) and examples/2)'-[P] ].
learn_cause(target_without_values(P)) --> !, [ 'target ~w has no values to learn'-[P] ].
learn_cause(target_without_facts(P)) --> !, [ 'target ~w has no facts'-[P] ].
learn_cause(target_type_mismatch(P, T, S)) --> !,
    [ 'target ~w is declared ~w but its values are ~q'-[P, T, S] ].
learn_cause(variable_goal) --> !, [ 'a variable as a goal'-[] ].
learn_cause(random_body(P)) --> !,
    [ '~w draws fresh randomness: not allowed in learning data'-[P] ].
learn_cause(bad_weight(T)) --> !,
    [ 'bad weight ~q: weight(Key, W) with a ground key and a number W > 0'-[T] ].
learn_cause(weighted_twice(K, W0, W)) --> !, [ '~q is given two weights, ~q and ~q'-[K, W0, W] ].
learn_cause(no_types(P)) --> !,
    [ 'a mode with + or - arguments needs the argument types of ~w: declare type(...) (or base/1)'-[P] ].
learn_cause(bad_model(Model, Spec)) --> !,
    [ 'the model ~q does not fit a target with values ~q'-[Model, Spec] ].
learn_cause(no_value(Key)) --> !, [ 'the example ~q has no value'-[Key] ].
learn_cause(too_many_worlds(Max)) --> !,
    [ 'a grounding splits into more than ~D partial worlds (uncertain facts it reads); raise max_worlds or make facts certain'-[Max] ].
learn_cause(goal_failed(_)) --> !, [ 'internal: an outcome goal failed'-[] ].
learn_cause(value_not_in_program(K, V, Vs)) --> !,
    [ '~q ~~= ~q: the program gives ~q no probability (its values: ~q)'-[K, V, V, Vs] ].
learn_cause(cyclic_targets(Ts)) --> !,
    [ 'the targets read each other (~w): order them with rank/1'-[Ts] ].
learn_cause(random_variable_as_atom(P)) --> !,
    [ '~w is a random variable: read it with ~~= (K ~~= V)'-[P] ].
learn_cause(C) --> [ '~q'-[C] ].
