/*  ddc_batch_program.pl -- the batched filter's view of a DDC program.

    Part of the batched particle filter (ddc_batch.pl, the API): which
    programs the batched engine evaluates (its fragment) and the program's
    clauses compiled into the facts the evaluation reads
    (ddc_batch_eval.pl).
*/

:- module(ddc_batch_program,
          [ batch_check_program/2,      % +Items, +File
            compile_batch_program/2,    % +Module, +Items
            timed_read/3                % +Read, -X, -TimeExpr
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(assoc)).
:- use_module('../lang/ddc_records').
:- use_module('../lang/ddc_body', [conj_from_list/2]).
:- use_module('../lang/ddc_ops').

:- set_prolog_flag(optimise, true).

/** <module> The batched filter's fragment and compiled program

batch_check_program/2 names the first clause of a program outside what
the batched filter evaluates (the fragment: ddc_batch.pl's header);
compile_batch_program/2 asserts, into the program's module, the facts the
batched evaluation reads (the per-particle engine's clauses, in the same
module, are untouched):

    '$b_rv'(X, Kind, Dist, Body, Origin)    Kind: zero, next, now
    '$b_der'(X, Kind, Body, Line)           Kind: next, now, zero
    '$b_static'(Head, Body)                 an untimed derived atom with a static body
    '$b_static_pred'(Head, Kind)            a static predicate: derived or plain
    '$b_lookback'(Name/Arity)               a derived predicate read at t by a transition
    '$b_exclusive'(Id1, Id2)                clause Id2 applies in no particle that clause Id1
                                            gives a value, and evaluating its body there
                                            draws nothing (see exclusive/3)
    '$b_visible'(Name/Arity, Bool)          (filled by the evaluation: a predicate visible
                                            from the module or not)

Origin is an origin/3 record (origin_line/2, origin_id/2,
origin_rivals/2): the clause's line and id in the program, and whether
a later clause of the same kind may define the same variable (and the
program does not declare first_applicable for it) that is not shown
exclusive with it ('$b_exclusive'/2): then the evaluation checks the
clause for overlaps (ddc_batch_eval:run_clause/9), evaluating each later
clause not shown exclusive in the checked particles that this one gave a
value.
*/

%   origin(Line, Id, Rivals): where a random variable's clause comes from
%   (its line, ddc_read.pl's clause id) and whether it has rivals (above).
:- record_type origin(line, id, rivals).

%   Items (ddc_read.pl's classified program):
%     rv(Id, X, Kind, Dist, Body, Line), der(Id, X, Kind, Body, Line),
%     plain(Clause, Line), rivals(Id, Rivals)
%   with Kind u, state, trans, fixed(N) or persist.

%!  batch_check_program(+Items:list, +File:atom) is det.
%
%   True if every clause of Items (ddc_read.pl's classified program) is in the
%   batched filter's fragment (ddc_batch.pl's header).
%
%   @error ddc(batched_unsupported(What), File:Line) for the first clause
%          outside it.
batch_check_program(Items, File) :-
    forall(member(I, Items), check_item(I, Items, File)).

check_item(rv(_, X, K, _, B, L), Items, File) :- !,
    (   memberchk(K, [trans, state, persist, fixed(0)]) -> true
    ;   unsupported(File, L, time_index(X, K))
    ),
    check_body(B, Items, K, File, L).
check_item(der(_, X, K, B, L), Items, File) :- !,
    (   K == u
    ->  (   static_body(B, Items) -> true
        ;   unsupported(File, L, untimed_derived_with_random_reads(X))
        )
    ;   memberchk(K, [trans, state, persist, fixed(0)]) -> check_body(B, Items, K, File, L)
    ;   unsupported(File, L, time_index(X, K))
    ).
check_item(_, _, _).

unsupported(File, L, What) :-
    throw(error(ddc(batched_unsupported(What), File:L), _)).

check_body(V, _, _, File, L) :- var(V), !, unsupported(File, L, variable_goal).
check_body((A, B), Is, K, F, L) :- !, check_body(A, Is, K, F, L), check_body(B, Is, K, F, L).
check_body((A ; B), Is, K, F, L) :- !, check_body(A, Is, K, F, L), check_body(B, Is, K, F, L).
check_body((A -> B), Is, K, F, L) :- !, check_body(A, Is, K, F, L), check_body(B, Is, K, F, L).
check_body(\+ A, Is, K, F, L) :- !, check_body(A, Is, K, F, L).
check_body(findall(_, G, _), Is, K, F, L) :- !, check_body(G, Is, K, F, L).
check_body(findall_forward(_, G, _), Is, K, F, L) :- !, check_body(G, Is, K, F, L).
check_body(X:TE ~= _, _, _, F, L) :- !, check_time(X, TE, F, L).
check_body(R0 ~= _, _, _, F, L) :- timed_read(R0, X, TE), !, check_time(X, TE, F, L).
check_body(X ~= _, _, _, F, L) :- !,
    (   nonvar(X), X = observation(_) -> true
    ;   unsupported(F, L, untimed_read(X))
    ).
check_body(G:TE, _, _, F, L) :- !,
    check_time(G, TE, F, L).
check_body(G, _, _, F, L) :-
    compound(G), functor(G, N, A),
    memberchk(N/A, [sample/2, true/1, belief/1, timestep/1, current/1, next/1, prior/1]), !,
    unsupported(F, L, G).
check_body(_, _, _, _, _).

check_time(X, TE, F, L) :-
    (   nonvar(TE), ( TE == t ; TE = T0+1, T0 == t ; TE == 0 ) -> true
    ;   unsupported(F, L, time(X:TE))
    ).

static_body(B, _) :- var(B), !, fail.
static_body((A, B), Is) :- !, static_body(A, Is), static_body(B, Is).
static_body((A ; B), Is) :- !, static_body(A, Is), static_body(B, Is).
static_body((A -> B), Is) :- !, static_body(A, Is), static_body(B, Is).
static_body(\+ A, Is) :- !, static_body(A, Is).
static_body(findall(_, G, _), Is) :- !, static_body(G, Is).
static_body(_ ~= _, _) :- !, fail.
static_body(_:_, _) :- !, fail.
static_body(G, Is) :-
    callable(G),
    \+ ( functor(G, N, A), functor(P, N, A),
         ( memberchk(rv(_, P, _, _, _, _), Is)
         ; memberchk(der(_, P, K, _, _), Is), K \== u
         ; memberchk(der(_, P, u, B, _), Is), \+ static_body(B, [])
         ) ).

%!  timed_read(+Read, -X, -TimeExpr) is semidet.
%
%   The original language's current(h), next(h) and prior(h) are h:t,
%   h:t+1 and h:0 (as in ddc_read.pl's heads and ddc_body.pl's reads).
timed_read(R, X, TE) :-
    nonvar(R),
    (   R = current(X) -> TE = t
    ;   R = next(X) -> TE = t+1
    ;   R = prior(X) -> TE = 0
    ),
    nonvar(X).

%!  compile_batch_program(+Module:atom, +Items:list) is det.
%
%   Asserts into Module the batched filter's view of the program Items
%   (the facts listed in the module documentation), replacing the ones of
%   an earlier program.
compile_batch_program(M, Items) :-
    retractall(M:'$b_rv'(_, _, _, _, _)),
    retractall(M:'$b_der'(_, _, _, _)),
    retractall(M:'$b_static'(_, _)),
    retractall(M:'$b_static_pred'(_, _)),
    retractall(M:'$b_lookback'(_)),
    retractall(M:'$b_visible'(_, _)),
    retractall(M:'$b_exclusive'(_, _)),
    forall(lookback(Items, NA), assertz(M:'$b_lookback'(NA))),
    findall(N/A, ( member(rv(_, X, _, _, _, _), Items), functor(X, N, A) ), Rvs0),
    sort(Rvs0, Rvs),
    findall(Id-R, member(rivals(Id, R), Items), RivalPairs),
    list_to_assoc(RivalPairs, RivalsOf),
    findall(rv(Id, X, K1, D, B, L, R),
            (   member(rv(Id, X, K, D0, B0, L), Items),
                kind(K, K1),
                ( get_assoc(Id, RivalsOf, R0) -> R = R0 ; R = false ),
                param_goals(D0, D, Ps),
                operand_reads(B0, Rvs, B1),
                conj_with(B1, Ps, B)
            ), Compiled),
    forall(member(der(_, X, K, B0, L), Items),
           (   K == u
           ->  assertz(M:'$b_static'(X, B0)), static_pred(M, X, derived)
           ;   kind(K, K1),
               operand_reads(B0, Rvs, B),
               assertz(M:'$b_der'(X, K1, B, L))
           )),
    forall(member(plain(C, _), Items),
           ( clause_head(C, H), callable(H) -> static_pred(M, H, plain) ; true )),
    forall(( member(rv(Id, X, K, _, B, _, true), Compiled),
             member(rv(Id2, X2, K, _, B2, _, _), Compiled), Id2 > Id,
             exclusive(M, K, X-B, X2-B2) ),
           assertz(M:'$b_exclusive'(Id, Id2))),
    forall(member(rv(Id, X, K, D, B, L, R0), Compiled),
           (   (   R0 == true,
                   \+ ( member(rv(Id2, X2, K, _, _, _, _), Compiled), Id2 > Id,
                        \+ X \= X2, \+ M:'$b_exclusive'(Id, Id2) )
               ->  R = false                  % (every later clause exclusive)
               ;   R = R0
               ),
               make_origin([line(L), id(Id), rivals(R)], Origin),
               assertz(M:'$b_rv'(X, K, D, B, Origin))
           )).

                 /*******************************
                 *     EXCLUSIVE CLAUSES        *
                 *******************************/

%   exclusive(+M, +Kind, +X1-Body1, +X2-Body2): no particle in which the first
%   clause's body holds makes the second's hold, for the same head, shown
%   from their top-level goals (a later clause's body fails, at the latest,
%   at a goal that contradicts one of the first's: h ~= a against
%   h ~= b, or h ~= V, V \== a; G against \+ G'; h ~= _ against \+ h ~= _;
%   findall(T, G, []) against findall(T, G, L), L \== []);
%   and evaluating the second body's goals up to that one in those
%   particles draws nothing and raises nothing (each reads a variable the
%   first body read, of a key made of head variables, or the first body's
%   findall, or an observation of the step, or is a test, a call of facts,
%   or, in a transition clause (Kind next), a derived atom at t, whose
%   instances are materialised):
%   the overlap check of the second clause in those particles would find
%   nothing and change nothing, so it is not made.
exclusive(M, K, X1-B1, X2-B2) :-
    copy_term(X1-B1, H-A),
    copy_term(X2-B2, H2-B),
    (   H \= H2
    ->  true                            % (never the same variable)
    ;   H = H2,
        term_variables(H, HVs),
        conj_goals(A, GA),
        conj_goals(B, GB),
        exclusive_goals(GB, M-K, GA, GB, HVs)
    ).

exclusive_goals([G|Gs], MK, GA, GB, HVs) :-
    (   contradicts(G, Gs, MK, GA, GB, HVs)
    ->  true
    ;   quiet_goal(G, MK, GA, HVs),
        exclusive_goals(Gs, MK, GA, GB, HVs)
    ).

%   conj_goals(+Body, -Goals): Body's top-level conjuncts, reads as
%   X:TE ~= P (current(h) as h:t, ...).
conj_goals(B, Gs) :-
    conj_goals(B, Gs, []).

conj_goals(B, Gs0, Gs) :- var(B), !, Gs0 = [B|Gs].
conj_goals((A, B), Gs0, Gs) :- !, conj_goals(A, Gs0, Gs1), conj_goals(B, Gs1, Gs).
conj_goals(true, Gs, Gs) :- !.
conj_goals(R ~= P, [X:TE ~= P|Gs], Gs) :- timed_read(R, X, TE), !.
conj_goals(\+ (R ~= P), [\+ (X:TE ~= P)|Gs], Gs) :- timed_read(R, X, TE), !.
conj_goals(G, [G|Gs], Gs).

%   contradicts(+G, +Rest, +M, +GA, +GB, +HVs): goal G of the second body
%   (Rest the goals after it) fails in every particle where the first
%   body's goals GA hold, drawing and raising nothing.
contradicts(G, _, _, GA, _, HVs) :-                      % h ~= b against h ~= a
    read_goal(G, K, C2), ground(C2), key_of_head(K, HVs),
    member(G1, GA), read_goal(G1, K1, C1), K1 == K,
    (   ground(C1)
    ->  different_values(C1, C2)
    ;   var(C1), \+ memberchk_eq(C1, HVs),               % h ~= V, V \== b
        member(T, GA), nonvar(T), T = (V1 \== C3), V1 == C1, C3 == C2,
        \+ number(C2)
    ), !.
contradicts(G, [T|_], _, GA, GB, HVs) :-                  % h ~= V, V \== a against h ~= a
    read_goal(G, K, V2), var(V2), key_of_head(K, HVs),
    only_in(V2, [G, T], GB),
    nonvar(T), T = (V3 \== C), V3 == V2, ground(C), \+ number(C),
    member(G1, GA), read_goal(G1, K1, C1), K1 == K, C1 == C, !.
contradicts(\+ G2, _, MK, GA, GB, HVs) :-                 % \+ G' against G
    callable(G2), quiet_call(G2, MK),
    local_vars(G2, \+ G2, GB, HVs),
    member(G1, GA), callable(G1), quiet_call(G1, MK),
    subsumes_term(G2, G1), !.
contradicts(G, _, MK, GA, _, HVs) :-                       % G against \+ G'
    callable(G), quiet_call(G, MK),
    member(N1, GA), nonvar(N1), N1 = (\+ G1), callable(G1), quiet_call(G1, MK),
    local_vars(G1, N1, GA, HVs),
    subsumes_term(G1, G), !.
contradicts(G, _, _, GA, _, HVs) :-                       % findall(.., []) against
    findall_goal(G, T, Q, L), L == [],                    %   findall(.., L), L \== []
    member(F, GA), findall_goal(F, T1, Q1, L1), var(L1),
    same_collection(T-Q, T1-Q1, HVs),
    member(N, GA), nonvar(N), N = (L2 \== E), L2 == L1, E == [], !.
contradicts(G, [N|_], _, GA, GB, HVs) :-                  % findall(.., L), L \== [] against
    findall_goal(G, T, Q, L), var(L),                     %   findall(.., [])
    nonvar(N), N = (L2 \== E), L2 == L, E == [],
    only_in(L, [G, N], GB),
    member(F, GA), findall_goal(F, T1, Q1, L1), L1 == [],
    same_collection(T-Q, T1-Q1, HVs), !.
contradicts(\+ G, _, _, GA, _, HVs) :-                   % \+ h ~= _ against h ~= _
    nonvar(G), read_goal(G, K, _), key_of_head(K, HVs),
    member(G1, GA), read_goal(G1, K1, _), K1 == K, !.
contradicts(G, _, _, GA, _, HVs) :-                       % h ~= _ against \+ h ~= _
    read_goal(G, K, _), key_of_head(K, HVs),
    member(N1, GA), nonvar(N1), N1 = (\+ G1), nonvar(G1), read_goal(G1, K1, _), K1 == K, !.

findall_goal(G, T, Q, L) :-
    nonvar(G), ( G = findall(T, Q, L) -> true ; G = findall_forward(T, Q, L) ).

%   same_collection(+TQ1, +TQ2, +HVs): the template and goal of two
%   findalls are the same but for their own variables (the head's the
%   same), so they collect the same list in every particle.
same_collection(TQ1, TQ2, HVs) :-
    \+ \+ ( foldl(head_constant, HVs, 0, _), TQ1 =@= TQ2 ).

head_constant(V, K0, K) :- V = '$head'(K0), K is K0+1.

%   quiet_goal(+G, +M, +GA, +HVs): G, evaluated where GA holds, draws and
%   raises nothing: a read of a key (of head variables) that GA reads too
%   (its values are there), a test == or \==, a call of facts.
quiet_goal(G, _, GA, HVs) :-
    read_goal(G, K, _), !,
    key_of_head(K, HVs),
    read_in(K, GA).
quiet_goal(G, _, _, _) :-
    nonvar(G), ( G = (_ == _) ; G = (_ \== _) ), !.
quiet_goal(G, _, _, _) :-                       % an observation of the step
    nonvar(G), G = (X ~= _), callable(X), X \= _:_, \+ timed_read(X, _, _), !.
quiet_goal(G, _, GA, HVs) :-                    % the same findall as the first body's
    findall_goal(G, T, Q, L), var(L), !,
    member(F, GA), findall_goal(F, T1, Q1, L1), var(L1),
    same_collection(T-Q, T1-Q1, HVs), !.
quiet_goal(G, MK, _, _) :-
    callable(G), quiet_call(G, MK).

read_in(K, GA) :-
    member(G1, GA), nonvar(G1),
    (   read_goal(G1, K1, _) -> true ; G1 = (\+ G2), nonvar(G2), read_goal(G2, K1, _) ),
    K1 == K, !.

read_goal(G, X:TE, P) :- nonvar(G), G = (X0:TE ~= P), nonvar(X0), X = X0, ground(TE).

key_of_head(K, HVs) :-
    term_variables(K, Vs),
    forall(member(V, Vs), memberchk_eq(V, HVs)).

memberchk_eq(X, [Y|Ys]) :- ( X == Y -> true ; memberchk_eq(X, Ys) ).

different_values(C1, C2) :-
    C1 \= C2,
    \+ ( number(C1), number(C2), C1 =:= C2 ).

%   local_vars(+G, +In, +Goals, +HVs): each variable of G is a head
%   variable or occurs in no goal of Goals but In.
local_vars(G, In, Goals, HVs) :-
    term_variables(G, Vs),
    forall(( member(V, Vs), \+ memberchk_eq(V, HVs) ),
           only_in(V, [In], Goals)).

only_in(V, Ins, Goals) :-
    forall(( member(G, Goals), \+ ( member(I, Ins), I == G ) ),
           ( term_variables(G, GVs), \+ memberchk_eq(V, GVs) )).

%   quiet_call(+G, +M-Kind): G calls facts: a static predicate all of whose
%   clauses are facts of the program (h := true), or a dynamic predicate
%   or one the program does not define (the step's facts: object(A),
%   observed(A)), or in a transition clause a derived atom at t (its
%   instances materialised at the step before: ddc_batch.pl's
%   materialise_derived/4).
quiet_call(G, M-K) :-
    G = D:TE, !,
    K == next, TE == t, callable(D),
    functor(D, N, A), M:'$b_lookback'(N/A).
quiet_call(G, M-_) :-
    \+ special_goal(G),
    functor(G, N, A), functor(P, N, A),
    (   M:'$b_static_pred'(P, Kind)
    ->  Kind == derived,
        forall(M:'$b_static'(P, B), B == true)
    ;   predicate_property(M:P, dynamic)
    ->  true
    ;   \+ predicate_property(M:P, visible)
    ).

special_goal(G) :-
    (   G = _:_ ; G = (_ ~= _) ; G = (_, _) ; G = (_ ; _) ; G = (_ -> _) ; G = (\+ _)
    ;   G = findall(_, _, _) ; G = findall_forward(_, _, _)
    ;   G = (_ is _) ; G = (_ = _)
    ;   functor(G, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=, ==, \==, @<, @>, @=<, @>=])
    ), !.

%   lookback(+Items, -N/A): a derived predicate that a transition body
%   reads at t: materialised at every step (ddc_batch:materialise_derived/4),
%   so that the next step reads its instances of the time before, as the
%   per-particle engine's sweep materialises them.
lookback(Items, N/A) :-
    findall(N0/A0, ( member(I, Items),
                     ( I = rv(_, _, K, _, B, _) ; I = der(_, _, K, B, _) ),
                     memberchk(K, [trans, persist]),
                     body_read_at_t(B, G),
                     functor(G, N0, A0), functor(P, N0, A0),
                     memberchk(der(_, P, K2, _, _), Items), K2 \== u ), L),
    sort(L, Ls),
    member(N/A, Ls).

body_read_at_t(B, _) :- var(B), !, fail.
body_read_at_t((A, B), G) :- !, ( body_read_at_t(A, G) ; body_read_at_t(B, G) ).
body_read_at_t((A ; B), G) :- !, ( body_read_at_t(A, G) ; body_read_at_t(B, G) ).
body_read_at_t((A -> B), G) :- !, ( body_read_at_t(A, G) ; body_read_at_t(B, G) ).
body_read_at_t(\+ A, G) :- !, body_read_at_t(A, G).
body_read_at_t(findall(_, A, _), G) :- !, body_read_at_t(A, G).
body_read_at_t(findall_forward(_, A, _), G) :- !, body_read_at_t(A, G).
body_read_at_t(_ ~= _, _) :- !, fail.
body_read_at_t(G0:TE, G) :- TE == t, callable(G0), G = G0.

%   (rivals(Id, R) items: ddc_compile.pl's rivals/3, whether a later clause can
%   define what clause Id defines: then overlaps are looked for.)

%   param_goals(+Dist0, -Dist, -Goals): Dist0 with each arithmetic
%   expression among its numeric parameters replaced by a variable that
%   Goals compute (V is Expr, run after the body: as ddc_world.pl's eval_dist/2
%   evaluates them), so that a parameter over columns is a deferred
%   expression like any other.
param_goals(D0, D, Goals) :-
    compound(D0), !,
    compound_name_arguments(D0, N, Args0),
    (   memberchk(N, [finite, propfinite, logfinite]), Args0 = [L0], is_list(L0)
    ->  foldl(pair_param, L0, L, [], Gs0), Args = [L]
    ;   N == val
    ->  Args = Args0, Gs0 = []
    ;   N == uniform, Args0 = [S0], nonvar(S0), S0 = A0:C0
    ->  param(A0, A, [], Gs1), param(C0, C, Gs1, Gs0), Args = [A:C]
    ;   N == uniform
    ->  Args = Args0, Gs0 = []
    ;   foldl(param, Args0, Args, [], Gs0)
    ),
    compound_name_arguments(D, N, Args),
    reverse(Gs0, Goals).
param_goals(D, D, []).

pair_param(P0:V, P:V, Gs0, Gs) :- !, param(P0, P, Gs0, Gs).
pair_param(X, X, Gs, Gs).

param(X, X, Gs, Gs) :- var(X), !.
param(X, X, Gs, Gs) :- number(X), !.
param([], [], Gs, Gs) :- !.
param([H0|T0], [H|T], Gs0, Gs) :- !, param(H0, H, Gs0, Gs1), param(T0, T, Gs1, Gs).
param((A0, B0), (A, B), Gs0, Gs) :- !, param(A0, A, Gs0, Gs1), param(B0, B, Gs1, Gs).
param(X, X, Gs, Gs) :- atom(X), \+ catch(_ is X, _, fail), !.
param(X, V, Gs, [V is X|Gs]).

conj_with(B, [], B) :- !.
conj_with(B, [G|Gs], (B, C)) :- conj_from_list([G|Gs], C).

%   operand_reads(+Body, +Rvs, -Body1): a comparison whose operand is a
%   random variable at a time (pos(1):t > 0, the paper's shorthand) reads
%   it first, as ddc_body.pl's compiler does.
operand_reads(V, _, V) :- var(V), !.
operand_reads((A, B), R, (A1, B1)) :- !, operand_reads(A, R, A1), operand_reads(B, R, B1).
operand_reads((A ; B), R, (A1 ; B1)) :- !, operand_reads(A, R, A1), operand_reads(B, R, B1).
operand_reads((A -> B), R, (A1 -> B1)) :- !, operand_reads(A, R, A1), operand_reads(B, R, B1).
operand_reads(\+ A, R, \+ A1) :- !, operand_reads(A, R, A1).
operand_reads(findall(T, A, L), R, findall(T, A1, L)) :- !, operand_reads(A, R, A1).
operand_reads(findall_forward(T, A, L), R, findall_forward(T, A1, L)) :- !,
    operand_reads(A, R, A1).
operand_reads(G, _, G1) :-
    compound(G), functor(G, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=]),
    G =.. [Op, A, B],
    ( rv_operand(A) ; rv_operand(B) ), !,
    operand(A, VA, RA), operand(B, VB, RB),
    G2 =.. [Op, VA, VB],
    conj_from_list([RA, RB, G2], G1).
operand_reads(G, _, G).

rv_operand(X) :- nonvar(X), X = Y:_, nonvar(Y), \+ number(X).

operand(A, V, (A ~= V)) :- rv_operand(A), !.
operand(A, A, true).

static_pred(M, H, Kind) :-
    functor(H, N, A), functor(P, N, A),
    (   M:'$b_static_pred'(P, _) -> true ; assertz(M:'$b_static_pred'(P, Kind)) ).

clause_head((H :- _), H) :- !.
clause_head(H, H).

%   kind(+ItemKind, -Kind): the kind of a compiled clause: next (h:t+1,
%   read at t+1), now (h:t) or zero (h:0).
kind(trans, next).
kind(persist, next).
kind(state, now).
kind(fixed(0), zero).
