/*  ddc_learn_syntax.pl -- the learning data's DC syntax in the internal
    form: time-indexed terms as static predicates, DC bodies as goals over
    the data module.
*/

:- module(ddc_learn_syntax,
          [ time_rename_items/3,        % +Data, +Items0, -Items
            internal_key/3,             % +Data, +DCKey, -Key
            dc_term/3,                  % +Data, +Internal, -DCTerm
            dc_goal/4                   % +Data, +DCGoal, -Goal, +Where
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../lang/ddc_models').

:- use_module('../lang/ddc_ops').

/** <module> DC syntax of learning data, internally

A time-indexed term p(X):t is the static predicate p_t(X), p(X):t+1 is
p_t1(X) (section 4 of the paper); dc_term/3 maps them back.  A random
variable p(K1, ..., Kn) with value V is the fact p(K1, ..., Kn, V) of the
data module, so a DC body's `K ~= V` is a call of that predicate.
*/

                 /*******************************
                 *             TIME             *
                 *******************************/

%   Time-indexed terms become static predicates: p(X):t -> p_t(X),
%   p(X):t+1 -> p_t1(X); '$ddcl_timed'(Internal, Base, t|t1) remembers the
%   mapping.  Anything else after a colon that is not a module qualifier
%   (p:t-1, p:0) is an error: learning data describe one step.

%!  time_rename_items(+Data, +Items0:list, -Items:list) is det.
%
%   Items0 with every time-indexed term renamed (time_rename/4).
%
%   @error ddc_learn(unsupported_time(T), File:Line) for a time other than
%          t and t+1.
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
