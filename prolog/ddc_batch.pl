/*  ddc_batch.pl -- the batched particle filter of the DDC engine.

    The engine's other filter (ddc_filter.pl) proves each particle's
    clauses one particle at a time.  This one evaluates each clause once
    for a *batch* of particles (docs/batched-filter.md): the particles'
    values of a random variable at a time are one column term
    c(V1, ..., VN); a clause body runs for a list of particle indices with
    its variables bound either to one value for the whole batch or to a
    column reference; goals whose inputs agree across the batch run once,
    arithmetic, comparisons, draws and densities run in one loop over the
    batch, and a goal that needs a particle's value as a term (a key
    argument such as pos(H), a static call) splits the batch by that value.

    ddc.pl's filter_new/5 (option engine(batched)) loads the program and
    hands its items here; the filter_* predicates dispatch on the state.
    The module knows nothing of the engine's stores.

    Semantics (as ddc_filter.pl's, see its header): a random variable's
    value in a particle is drawn lazily, at most once, from the first
    applicable clause (h:0 or h:t+1, then h:t as a fallback); a step
    weighs each observation by its first applicable clause's density
    (none: an error), sweeps the transition clauses' ground heads, keeps
    time t for queries and drops t-1; overlapping clauses are an error,
    looked for in the first 20 particles.  The random draws come in
    another order (clause by clause over the particles), so the same seed
    gives other particles than the per-particle engine
    (docs/batched-filter.md, "What differs").

    Fragment (batch_check_program/2 names the first clause outside it,
    file:line): random variables h:0, h:t+1 and h:t; derived atoms h:t+1
    and h:t read at t+1 or in queries (not read at t in a transition body:
    those the per-particle engine materialises); static predicates (facts,
    plain Prolog clauses, untimed derived atoms with static bodies), the
    step's facts (actions, plain observations); bodies of conjunctions,
    \+, if-then-else, disjunction, reads h:t ~= P, h:t+1 ~= P, h:0 ~= P
    (current(h), next(h), prior(h) alike),
    untimed reads of an observation of the step, is/2, comparisons (a
    random variable h:t as an operand reads it), ==, \==, =, findall/3 and
    findall_forward/3, logistic/3 and linear/3, calls of static predicates
    and of Prolog's builtins; distribution parameters may be arithmetic
    expressions.
*/

:- module(ddc_batch,
          [ batch_check_program/2,      % +Items, +File
            batch_new/6,                % +Module, +Items, +N, +Seed, +Threads, -State
            batch_step/4,               % +State0, +Observations, +Facts, -Result
            batch_resample/3,           % +State0, +Indices, -State
            batch_holds/3,              % +State, +Goal, -Flags
            batch_values/4,             % +State, +Template, +Goal, -Values
            batch_time/2,               % +State, -T
            batch_size/2,               % +State, -N
            batch_keep/2,               % +State, -Kept
            batch_module/2,             % +State, -Module
            overlap_checked_particles/1 % -N
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(library(assoc)).
:- use_module(ddc_dist).
:- use_module(ddc_models, []).

:- set_prolog_flag(optimise, true).

:- op(700, xfx, ~).
:- op(700, xfx, ~=).
:- op(1105, xfx, :=).

/** <module> Batched particle filter for DDC programs

A filter state is bs(Prog, N, T, Tabs, Facts, Rng): Prog the compiled
program, Tabs the column tables of times T-1 and T (t(T-1, Tab1, T, Tab)),
Facts the facts of time T, Rng the state of the filter's random generator.
A state is never changed by a step or a resampling (they return a new
one), so the caller keeps the previous state for undo and for errors.
*/

                 /*******************************
                 *            PROGRAM           *
                 *******************************/

%   Items (ddc.pl's classified program):
%     rv(Id, X, Kind, Dist, Body, Line), der(Id, X, Kind, Body, Line),
%     plain(Clause, Line)   with Kind u, state, trans, fixed(N) or persist.
%   Compiled into Module (the program's own module, which also holds the
%   per-particle engine's code; the batched clauses are facts of their own):
%     '$b_rv'(X, Kind, Dist, Body, At)        Kind: zero, next, now;
%         At = at(Line, Id, Rivals): Rivals true if a later clause of the
%         same kind may define the same variable (and the program does not
%         declare first_applicable for it): then checked for overlaps
%     '$b_der'(X, Kind, Body, Line)           Kind: next, now, zero
%     '$b_static'(Head, Body)                 untimed derived with a static body

%!  batch_check_program(+Items, +File) is det.
%
%   Throws error(ddc(batched_unsupported(What), File:Line), _) for the
%   first clause of Items outside the batched filter's fragment (see the
%   file header).
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

%   compile(+Module, +Items): the batched filter's view of the program.
compile(M, Items) :-
    retractall(M:'$b_rv'(_, _, _, _, _)),
    retractall(M:'$b_der'(_, _, _, _)),
    retractall(M:'$b_static'(_, _)),
    retractall(M:'$b_static_pred'(_, _)),
    retractall(M:'$b_lookback'(_)),
    retractall(M:'$b_visible'(_, _)),
    forall(lookback(Items, NA), assertz(M:'$b_lookback'(NA))),
    findall(N/A, ( member(rv(_, X, _, _, _, _), Items), functor(X, N, A) ), Rvs0),
    sort(Rvs0, Rvs),
    findall(Id-R, member(rivals(Id, R), Items), RivalPairs),
    list_to_assoc(RivalPairs, RivalsOf),
    forall(member(rv(Id, X, K, D0, B0, L), Items),
           (   kind(K, K1),
               ( get_assoc(Id, RivalsOf, R0) -> R = R0 ; R = false ),
               param_goals(D0, D, Ps),
               operand_reads(B0, Rvs, B1),
               conj_with(B1, Ps, B),
               assertz(M:'$b_rv'(X, K1, D, B, at(L, Id, R)))
           )),
    forall(member(der(_, X, K, B0, L), Items),
           (   K == u
           ->  assertz(M:'$b_static'(X, B0)), static_pred(M, X, derived)
           ;   kind(K, K1),
               operand_reads(B0, Rvs, B),
               assertz(M:'$b_der'(X, K1, B, L))
           )),
    forall(member(plain(C, _), Items),
           ( clause_head(C, H), callable(H) -> static_pred(M, H, plain) ; true )).

%   lookback(+Items, -N/A): a derived predicate that a transition body
%   reads at t: materialised at every step (materialise_derived/3), so
%   that the next step reads its instances of the time before, as the
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

%   (rivals(Id, R) items: ddc.pl's rivals/7, whether a later clause can
%   define what clause Id defines: then overlaps are looked for.)

%   param_goals(+Dist0, -Dist, -Goals): Dist0 with each arithmetic
%   expression among its numeric parameters replaced by a variable that
%   Goals compute (V is Expr, run after the body: as ddc.pl's eval_dist/2
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
conj_with(B, [G|Gs], (B, C)) :- list_conj([G|Gs], C).

%   operand_reads(+Body, +Rvs, -Body1): a comparison whose operand is a
%   random variable at a time (pos(1):t > 0, the paper's shorthand) reads
%   it first, as ddc.pl's compiler does.
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
    list_conj([RA, RB, G2], G1).
operand_reads(G, _, G).

rv_operand(X) :- nonvar(X), X = Y:_, nonvar(Y), \+ number(X).

operand(A, V, (A ~= V)) :- rv_operand(A), !.
operand(A, A, true).

static_pred(M, H, Kind) :-
    functor(H, N, A), functor(P, N, A),
    (   M:'$b_static_pred'(P, _) -> true ; assertz(M:'$b_static_pred'(P, Kind)) ).

clause_head((H :- _), H) :- !.
clause_head(H, H).

kind(trans, next).
kind(persist, next).
kind(state, now).
kind(fixed(0), zero).

                 /*******************************
                 *            COLUMNS           *
                 *******************************/

%   A table of one time: Key -> e(Column, Status, Arity), Status one of
%   open (some particle may lack its value: '$u'), same(V) (every particle
%   holds V, '$undef' where no clause applied), defined (each particle a
%   value of its own), mixed (some undefined).  A fixed number of bucket
%   chains; an entry is copied once, when put, and then updated in place,
%   so that a column taken from the table stays the table's own.  Arity:
%   the tuple arity of all of a defined column's values, unknown until
%   found (entry_arity/2), or none.
tab_new(T) :- functor(T, tab, 1024).

tab_get(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L), nonvar(L), memberchk(K-E0, L), E = E0.

tab_put(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L),
    duplicate_term(K-E, KE),        % (a term made by unification may be undone)
    (   var(L) -> nb_linkarg(I, T, [KE]) ; nb_linkarg(I, T, [KE|L]) ).

%   tab_link(+T, +K, +E): as tab_put/3 for an entry made by construction
%   (no binding to undo): linked, not copied.
tab_link(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L),
    (   var(L) -> nb_linkarg(I, T, [K-E]) ; nb_linkarg(I, T, [K-E|L]) ).

tab_match(T, K, E) :-
    arg(_, T, L), nonvar(L), member(K-E, L).

new_column(N, V, C) :-
    functor(C, c, N),
    fill(N, C, V).

fill(0, _, _) :- !.
fill(I, C, V) :- arg(I, C, V), I1 is I-1, fill(I1, C, V).

                 /*******************************
                 *         ENVIRONMENT          *
                 *******************************/

%   env(Module, N, Now, Tabs, Facts, Obs, _): Now is the time that t means in
%   the body being evaluated; Tabs t(T0, Tab0, T1, Tab1) the tables held
%   (T1 the latest: values of T0 are only read, a value T0 lacks is
%   undefined, as in the per-particle filter's frozen time); Facts the
%   facts of the latest time; Obs its observations H-V.
env_time_table(env(_, _, _, Tabs, _, _, _), T, Tab) :-
    Tabs = t(T0, Tab0, T1, Tab1),
    (   T == T1 -> Tab = Tab1
    ;   T == T0, Tab0 \== none
    ->  (   Tab0 = pending(_, _)
        ->  real_table(Tab0, Tab),          % (kept for the next query)
            nb_linkarg(2, Tabs, Tab)
        ;   Tab = Tab0
        )
    ).

env_now(env(M, N, _, Tabs, Fs, Os, Ck), Now, env(M, N, Now, Tabs, Fs, Os, Ck)).

read_time(t, env(_, _, Now, _, _, _, _), Now) :- !.
read_time(T0+1, env(_, _, Now, _, _, _, _), T) :- T0 == t, !, T is Now+1.
read_time(T0-1, env(_, _, Now, _, _, _, _), T) :- T0 == t, !, T is Now-1.
read_time(0, _, 0).

                 /*******************************
                 *          EVALUATION          *
                 *******************************/

%   Body variables are bound to values (the same for the whole batch) or
%   to column references '$c'(C, Pattern, V): the particle's value in
%   column C unifies with Pattern, whose variable V is the variable's value
%   (Pattern = V for a plain read; a tuple of fresh variables, one of
%   them V, for a read such as pos(O):t ~= (X, Y, Z), whose three
%   references share the one Pattern: one unification per particle binds
%   all three), or to a deferred expression '$x'(Expr): `V is Expr` over
%   columns is not computed into a column of its own but evaluated in the
%   loop of each goal that reads V (a comparison, a draw, a head's value),
%   so that X1 is X + DX, Y1 is ..., then val((X1, Y1, Z1)) costs one loop
%   over the batch, not four.  A goal that needs V's value as a term (a
%   split) gets it computed into a column first (materialise/3).

%   plan(+T, -Tmpl, -Binds): Tmpl is T with each '$c'(C, Pattern, V)
%   replaced by V and each '$x'(Expr) by a variable W, Binds the C-Pattern
%   pairs and '$e'(W, ExprTmpl, '$x'(Expr)) evaluations (each once, an
%   evaluation after the bindings it reads): bind/2 makes Tmpl a
%   particle's instance.
plan(T, Tmpl, Binds) :-
    map_term(plan_leaf, T, Tmpl, [], Binds0),
    reverse(Binds0, Binds).

plan_leaf('$c'(C, P, V), V, Bs0, Bs) :-
    (   member(C0-P0, Bs0), C0 == C, P0 == P -> Bs = Bs0 ; Bs = [C-P|Bs0] ).
plan_leaf(X, W, Bs0, Bs) :-
    X = '$x'(Ex),
    (   member('$e'(W0, _, X0), Bs0), X0 == X
    ->  W = W0, Bs = Bs0
    ;   map_term(plan_leaf, Ex, ExT, Bs0, Bs1),
        Bs = ['$e'(W, ExT, X)|Bs1]
    ).

%   map_term(:Leaf, +T, -T1, +A0, -A): T with each subterm S for which
%   call(Leaf, S, S1, A0, A) succeeds replaced by S1 (its arguments not
%   visited), the others copied, A threaded through the leaves from left
%   to right.
:- meta_predicate map_term(4, +, -, +, -).
map_term(_, T, T, A, A) :- var(T), !.
map_term(Leaf, T, T1, A0, A) :- call(Leaf, T, T1, A0, A), !.
map_term(_, T, T, A, A) :- atomic(T), !.
map_term(Leaf, T, T1, A0, A) :-
    compound_name_arguments(T, F, As),
    map_args(As, Leaf, As1, A0, A),
    compound_name_arguments(T1, F, As1).

map_args([], _, [], A, A).
map_args([X|Xs], Leaf, [Y|Ys], A0, A) :-
    map_term(Leaf, X, Y, A0, A1),
    map_args(Xs, Leaf, Ys, A1, A).

bind([], _).
bind([B|Bs], I) :- bind_one(B, I), bind(Bs, I).

bind_one(C-P, I) :- arg(I, C, P).
bind_one('$e'(W, Ex, _), _) :- W is Ex.

col_ref(C, V, '$c'(C, V, V)).

has_col(T) :-
    compound(T),
    (   T = '$c'(_, _, _) -> true ; T = '$x'(_) -> true ; arg(_, T, A), has_col(A) ), !.

%   materialise(+T, +Ps, -T1): T with each deferred expression computed
%   into a column, for the particles Ps.
materialise(T, Ps, T1) :-
    (   deferred_in(T, X)
    ->  X = '$x'(Ex),
        once(column_in(Ex, C0)),
        functor(C0, _, N),
        plan(X, W, Bs),
        functor(C, c, N),
        arith_loop(Ps, Bs, W, C),
        col_ref(C, _, Ref),
        replace_eq(T, X, Ref, T2),
        materialise(T2, Ps, T1)
    ;   T1 = T
    ).

%   deferred_in(+T, -X): a deferred expression in T (not looking inside
%   column references: a column has an argument per particle).
deferred_in(T, X) :-
    compound(T),
    (   T = '$x'(_) -> X = T
    ;   T = '$c'(_, _, _) -> fail
    ;   arg(_, T, A), deferred_in(A, X)
    ), !.

%   column_in(+Ex, -C): a column Ex reads.
column_in(T, C) :-
    compound(T),
    (   T = '$c'(C0, _, _) -> C = C0
    ;   arg(_, T, A), column_in(A, C)
    ).

replace_eq(T, X, Y, T1) :-
    map_term(replace_leaf(X, Y), T, T1, none, _).

replace_leaf(X, Y, T, T1, A, A) :-
    (   T == X -> T1 = Y
    ;   T = '$c'(_, _, _) -> T1 = T             % (a column: not walked)
    ).


%   beval(+Body, +Env, +Ps0, -Ps): the body for the particles Ps0 (a sorted
%   list of indices, not empty); nondeterministic over branches (solutions
%   of goals the batch agrees on, splits by value), Ps the particles of the
%   branch, each in at most one branch per solution of their own.
beval(_, _, [], _) :- !, fail.
beval(G, _, _, _) :- var(G), !,
    throw(error(instantiation_error, _)).
beval(true, _, Ps, Ps) :- !.
beval((A, B), E, Ps0, Ps) :- !,
    beval(A, E, Ps0, Ps1),
    beval(B, E, Ps1, Ps).
beval((C -> T ; F), E, Ps0, Ps) :- !,
    if_then_else(C, T, F, E, Ps0, Ps).
beval((C -> T), E, Ps0, Ps) :- !,
    if_then_else(C, T, fail, E, Ps0, Ps).
beval((A ; B), E, Ps0, Ps) :- !,
    (   beval(A, E, Ps0, Ps) ; beval(B, E, Ps0, Ps) ).
beval(\+ G, E, Ps0, Ps) :- !,
    branch_union(G, E, Ps0, Done),
    ord_subtract(Ps0, Done, Ps),
    Ps \== [].
beval(findall_forward(T, G, L), E, Ps0, Ps) :- !,
    collect(T, G, L, E, Ps0, Ps).
beval(findall(T, G, L), E, Ps0, Ps) :- !,
    collect(T, G, L, E, Ps0, Ps).
beval(X:TE ~= P, E, Ps0, Ps) :- !,
    read_time(TE, E, T),
    split(X, Ps0, X1, Ps1),
    read_key(X1, T, E, Ps1, K, Entry, Ps2),
    unify_read(P, K, Entry, Ps2, Ps).
beval(R0 ~= P, E, Ps0, Ps) :-                    % the original's current(h) = h:t, ...
    timed_read(R0, X, TE), !,
    beval(X:TE ~= P, E, Ps0, Ps).
beval(X ~= P, E, Ps0, Ps) :- !,                   % an observation of the step
    split(X, Ps0, X1, Ps1),
    E = env(_, _, _, _, _, Obs, _),
    member(X1-V, Obs),
    unify_value(P, V, Ps1, Ps).
beval(G:TE, E, Ps0, Ps) :- !,                     % a derived atom at a time
    read_time(TE, E, T),
    split(G, Ps0, G1, Ps1),
    derived(G1, T, E, Ps1, Ps).
beval(V is Ex, _, Ps0, Ps) :- !,
    arith_value(V, Ex, Ps0, Ps).
beval(linear(Is, Ws, Y), _, Ps0, Ps) :- !,
    linear_expr(Is, Ws, Ex),
    arith_value(Y, Ex, Ps0, Ps).
beval(logistic(Is, Ws, P), _, Ps0, Ps) :- !,        % (1+tanh(z/2))/2 = 1/(1+exp(-z)),
    linear_expr(Is, Ws, Ex),                        %  without exp's overflow
    arith_value(P, (1 + tanh(Ex/2))/2, Ps0, Ps).
beval(A = B, _, Ps0, Ps) :-                      % binds a variable side as it is
    ( var(A) ; var(B) ), !,
    A = B,
    Ps = Ps0.
beval(G, E, Ps0, Ps) :-
    (   has_col(G)
    ->  (   test_goal(G), \+ has_free_var(G)
        ->  test_loop(G, Ps0, Ps)
        ;   split(G, Ps0, G1, Ps1),
            call_static(G1, E),
            Ps = Ps1
        )
    ;   call_static(G, E),
        Ps = Ps0
    ).

%   linear_expr(+Inputs, +Weights, -Expr): w1*x1 + ... + wn*xn + b, with
%   Weights = [w1, ..., wn, b] (ddc.pl's linear/3).
linear_expr(Is, Ws, Ex) :-
    must_be(list, Is), must_be(list, Ws),
    length(Is, N), N1 is N+1,
    (   length(Ws, N1) -> true
    ;   domain_error(weights_one_more_than_inputs(N), Ws)
    ),
    weighted_sum(Is, Ws, Ex).

weighted_sum([], [B], B).
weighted_sum([X|Xs], [W|Ws], W*X + Ex) :- weighted_sum(Xs, Ws, Ex).

%   arith_value(?V, +Ex, +Ps0, -Ps): V is Ex, over columns or not.
arith_value(V, Ex, Ps0, Ps) :-
    (   has_col(Ex), var(V) -> V = '$x'(Ex), Ps = Ps0
    ;   ( has_col(V) ; has_col(Ex) ) -> test_loop(V =:= Ex, Ps0, Ps)
    ;   V is Ex, Ps = Ps0
    ).

%   has_free_var(+T): T has a variable of its own (not one inside a column
%   reference or a deferred expression, which each particle binds).
has_free_var(T) :- var(T), !.
has_free_var(T) :-
    compound(T), T \= '$c'(_, _, _), T \= '$x'(_),
    arg(_, T, A), has_free_var(A), !.

%   A goal run particle by particle as a test: no variables to bind (all
%   bound to values or columns) and a comparison or unification.
test_goal(G) :-
    compound(G), functor(G, Op, 2),
    memberchk(Op, [<, >, =<, >=, =:=, =\=, ==, \==, =, \=, @<, @>, @=<, @>=]).

arith_loop([], _, _, _).
arith_loop([I|Is], Bs, Ex, C) :-
    \+ \+ ( bind(Bs, I), X is Ex, nb_setarg(I, C, X) ),
    arith_loop(Is, Bs, Ex, C).

test_loop(G, Ps0, Ps) :-
    plan(G, Tmpl, Bs),
    (   Ps0 = [_, _, _, _, _, _, _, _, _, _, _, _, _, _, _, _|_]
    ->  compiled_test(Ps0, Bs, Tmpl, Ps)
    ;   test_each(Ps0, Bs, Tmpl, Ps)
    ),
    Ps \== [].

%   compiled_test(+Ps0, +Binds, +Test, -Ps): test_each/4 as a loop compiled
%   for the goal (its arithmetic compiled to virtual-machine instructions,
%   as the per-particle engine's clauses are; a particle's values bound by
%   unification in the clause, no undo between particles), for batches
%   large enough to pay for it.  A loop is compiled once per shape of goal:
%   its numbers are arguments (they change from step to step), so the
%   number of loops is bounded by the program's goals, and none is ever
%   retracted (a retracted clause waits for the clause garbage collector,
%   which a forked process, such as anchoring evaluate's workers, does not
%   have: loops asserted and retracted per batch made each run there seven
%   times slower).
compiled_test(Ps0, Bs, Tmpl, Ps) :-
    bind_goals(Bs, I, Cs, CVs, Gets, Evals),
    append([Gets, Evals, [Tmpl]], Gs),
    list_conj(Gs, Cond0),
    abstract_numbers(Cond0, Cond, Ks),
    pairs_keys_values(Ks, KVs, Ns),
    Head =.. [cols|CVs],
    compiled_loop(test, Head, k(KVs), I, Cond, Name),
    Cols =.. [cols|Cs],
    call(Name, Ps0, Cols, k(Ns), Ps).

%   compiled_instance(+Ps, +Binds, +Tmpl, +C): instance_each/4 as a
%   compiled loop (see compiled_test/4).
compiled_instance(Ps, Bs, Tmpl, C) :-
    bind_goals(Bs, I, Cs, CVs, Gets, Evals),
    append(Gets, Evals, Gs0),
    (   Gs0 == [] -> Cond1 = true ; list_conj(Gs0, Cond1) ),
    abstract_numbers(Cond1-Tmpl, Cond-Value, Ks),
    pairs_keys_values(Ks, KVs, Ns),
    Head =.. [cols|CVs],
    compiled_loop(instance(Value), Head, k(KVs), I, Cond, Name),
    Cols =.. [cols|Cs],
    call(Name, Ps, Cols, k(Ns), C).

%   compiled_loop(+Kind, +Head, +Consts, ?I, +Cond, -Name): the loop
%   predicate Name/4 for this shape (Name(Ps, Cols, Consts, Out)), made the
%   first time (under a mutex: threads share it).
compiled_loop(Kind, Head, Consts, I, Cond, Name) :-
    Shape = loop(Kind, Head, Consts, I, Cond),
    variant_sha1(Shape, Sha),
    atom_concat('$b_loop_', Sha, Name),
    (   '$b_loop_ready'(Name)
    ->  true
    ;   with_mutex('$ddc_batch_loops',
                   (   '$b_loop_ready'(Name) -> true
                   ;   copy_term(Shape, loop(Kind1, Head1, Consts1, I1, Cond1)),
                       loop_clauses(Kind1, Name, Head1, Consts1, I1, Cond1, Clauses),
                       optimised_assert(Clauses),
                       compile_predicates([Name/4]),
                       assertz('$b_loop_ready'(Name))   % (last: another thread may look)
                   ))
    ).

:- dynamic '$b_loop_ready'/1.

loop_clauses(test, Name, Head, Consts, I, Cond,
             [ Base, (Rec :- ( Cond -> Out = [I|Out1] ; Out = Out1 ), Next) ]) :-
    Base =.. [Name, [], _, _, []],
    Rec =.. [Name, [I|Is], Head, Consts, Out],
    Next =.. [Name, Is, Head, Consts, Out1].
loop_clauses(instance(Value), Name, Head, Consts, I, Cond,
             [ Base, (Rec :- ( arg(I, Out, U), U == '$u', Cond -> nb_setarg(I, Out, Value)
                              ; true ), Next) ]) :-
    Base =.. [Name, [], _, _, _],
    Rec =.. [Name, [I|Is], Head, Consts, Out],
    Next =.. [Name, Is, Head, Consts, Out].

%   abstract_numbers(+T, -T1, -Pairs): T with each number a variable;
%   Pairs the Variable-Number pairs, in order.
abstract_numbers(T, T1, Ps) :-
    map_term(number_leaf, T, T1, Ps, []).

number_leaf(T, V, [V-T|Ps], Ps) :- number(T).

%   bind_goals(+Binds, ?I, -Columns, -ColumnVars, -Gets, -Evals): the goals
%   that bind/2 runs for particle I, each column a variable (a clause must
%   not hold a column: asserting it would copy it).
bind_goals([], _, [], [], [], []).
bind_goals([C-P|Bs], I, [C|Cs], [CV|CVs], [arg(I, CV, P)|Gs], Es) :- !,
    bind_goals(Bs, I, Cs, CVs, Gs, Es).
bind_goals(['$e'(W, Ex, _)|Bs], I, Cs, CVs, Gs, [W is Ex|Es]) :-
    bind_goals(Bs, I, Cs, CVs, Gs, Es).

list_conj([G], G) :- !.
list_conj([G|Gs], (G, C)) :- list_conj(Gs, C).

optimised_assert(Clauses) :-
    current_prolog_flag(optimise, Old),
    setup_call_cleanup(set_prolog_flag(optimise, true),
                       forall(member(C, Clauses), assertz(C)),
                       set_prolog_flag(optimise, Old)).

test_each([], _, _, []).
test_each([I|Is], Bs, G, Ps) :-
    (   \+ \+ ( bind(Bs, I), call(G) ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    test_each(Is, Bs, G, Ps1).

%   call_static(+G, +Env): a static predicate of the program, a fact of
%   the step, or a builtin.
call_static(G, E) :-
    E = env(M, _, _, _, Facts, _, _),
    (   M:'$b_static_pred'(G, Kind)
    ->  (   Kind == derived -> M:'$b_static'(G, B), static_body_call(B, E) ; M:G )
    ;   model_goal(G)                                  % softmax/3, mean_list/2, ...
    ->  ddc_models:G
    ;   visible(M, G)
    ->  M:G
    ;   member(G, Facts)
    ).

%   model_goal(+G): G is one of library ddc_models' (without asking
%   predicate_property/2, which looks for G in the autoload index when the
%   answer is no).
model_goal(G) :-
    functor(G, N, A),
    module_property(ddc_models, exports(Es)),
    memberchk(N/A, Es).

%   visible(+M, +G): G's predicate is defined in M or reachable from it
%   (imported, a builtin, autoloadable).  Asked once per predicate and
%   program: predicate_property(M:G, visible) searches the autoload index
%   each time the answer is no (a fact of the step, such as category/2,
%   asked for in every particle at every step).
visible(M, G) :-
    functor(G, N, A),
    (   M:'$b_visible'(N/A, V)
    ->  V == true
    ;   (   predicate_property(M:G, visible) -> V = true ; V = false ),
        assertz(M:'$b_visible'(N/A, V)),
        V == true
    ).

%   static_body_call(+B, +E): an untimed derived atom's body, whose goals
%   may be the step's facts (can_occlude(O) := category(O, C), ...).
static_body_call(V, _) :- var(V), !, throw(error(instantiation_error, _)).
static_body_call(true, _) :- !.
static_body_call((A, B), E) :- !, static_body_call(A, E), static_body_call(B, E).
static_body_call((A ; B), E) :- !,
    (   nonvar(A), A = (C -> T)
    ->  ( static_body_call(C, E) -> static_body_call(T, E) ; static_body_call(B, E) )
    ;   ( static_body_call(A, E) ; static_body_call(B, E) )
    ).
static_body_call((C -> T), E) :- !, ( static_body_call(C, E) -> static_body_call(T, E) ).
static_body_call(\+ A, E) :- !, \+ static_body_call(A, E).
static_body_call(findall(X, A, L), E) :- !, findall(X, static_body_call(A, E), L).
static_body_call(G, E) :- call_static(G, E).

%   split(+T, +Ps0, -T1, -Ps): T with its column references replaced by
%   the particles' values, for each group of particles that share them.
%   (Only the columns' values are grouped: T's own unbound variables stay
%   T1's, for the goals after it.)
split(T0, Ps0, T1, Ps) :-
    (   has_col(T0)
    ->  materialise(T0, Ps0, T),
        plan(T, Tmpl, Bs),
        pairs_keys_values(Bs, Cs, Pats),
        split_pairs(Ps0, Cs, Pairs),
        keysort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups),
        member(Pats-Ps, Groups),
        T1 = Tmpl
    ;   T1 = T0, Ps = Ps0
    ).

split_pairs([], _, []).
split_pairs([I|Is], Cs, [Vs-I|Ps]) :-
    args_at(Cs, I, Vs),
    split_pairs(Is, Cs, Ps).

args_at([], _, []).
args_at([C|Cs], I, [V|Vs]) :- arg(I, C, V), args_at(Cs, I, Vs).

branch_union(G, E, Ps0, Union) :-
    findall(Ps, beval(G, E, Ps0, Ps), Ls),
    ord_union(Ls, Union).

%   if_then_else(+C, +T, +F, +E, +Ps0, -Ps): each particle takes T with
%   C's first solution of its own, or F if C has none.
if_then_else(C, T, F, E, Ps0, Ps) :-
    findall(Ps1, beval(C, E, Ps0, Ps1), Ls),
    firsts(Ls, [], Firsts, Taken),
    (   Counter = count(0),
        beval(C, E, Ps0, Ps1),
        arg(1, Counter, K0), K is K0+1, nb_setarg(1, Counter, K),
        nth1(K, Firsts, Ps2),
        ord_intersection(Ps1, Ps2, Ps3),
        Ps3 \== [],
        beval(T, E, Ps3, Ps)
    ;   ord_subtract(Ps0, Taken, Rest),
        Rest \== [],
        beval(F, E, Rest, Ps)
    ).

firsts([], Taken, [], Taken).
firsts([L|Ls], Taken0, [F|Fs], Taken) :-
    ord_subtract(L, Taken0, F),
    ord_union(Taken0, F, Taken1),
    firsts(Ls, Taken1, Fs, Taken).

%   collect(+T, +G, ?L, +E, +Ps0, -Ps): findall per particle.
collect(T, G, L, E, Ps0, Ps) :-
    E = env(_, N, _, _, _, _, _),
    functor(LC, c, N),
    set_all(Ps0, LC, []),
    forall(beval(G, E, Ps0, Ps1),
           ( plan(T, Tmpl, Bs), append_each(Ps1, Bs, Tmpl, LC) )),
    (   Ps0 = [I0|_], arg(I0, LC, L0), all_same(Ps0, LC, L0)
    ->  unify_value(L, L0, Ps0, Ps)
    ;   unify_column(L, LC, Ps0, Ps)
    ).

set_all([], _, _).
set_all([I|Is], C, V) :- nb_setarg(I, C, V), set_all(Is, C, V).

all_same([], _, _).
all_same([I|Is], C, V) :- arg(I, C, V1), V1 == V, all_same(Is, C, V).

append_each([], _, _, _).
append_each([I|Is], Bs, Tmpl, LC) :-
    \+ \+ ( bind(Bs, I), arg(I, LC, L0), append(L0, [Tmpl], L1), nb_setarg(I, LC, L1) ),
    append_each(Is, Bs, Tmpl, LC).

%   unify_value(?P, +V, +Ps0, -Ps): P with a value the batch agrees on.
unify_value(P, V, Ps, Ps) :-
    (   has_col(P)
    ->  fail
    ;   P = V -> true
    ;   number(P), number(V), P =:= V
    ), !.
unify_value(P, V, Ps0, Ps) :-
    has_col(P),
    test_loop(P = V, Ps0, Ps).

%   unify_column(?P, +C, +Ps0, -Ps): P with each particle's value in C
%   (none undefined).
%   Arity: the tuple arity all values in C have (a number) or unknown.
unify_column(P, C, Ps0, Ps) :-
    unify_column(P, C, unknown, Ps0, Ps).

unify_column(P, C, Arity, Ps0, Ps) :-
    (   var(P)
    ->  col_ref(C, _, P), Ps = Ps0
    ;   tuple_of_vars(P, Vs)
    ->  length(Vs, K),
        (   Arity == K -> Ps = Ps0 ; with_arity(Ps0, C, K, Ps), Ps \== [] ),
        copy_term(P, Pat),
        term_variables(Pat, PVs),
        maplist(element_ref(C, Pat), Vs, PVs)
    ;   ground(P), \+ has_col(P)
    ->  with_value(Ps0, C, P, Ps), Ps \== []
    ;   plan(P, Tmpl, Bs),
        unifiable_at(Ps0, C, Bs, Tmpl, Ps1),
        Ps1 \== [],
        split_column(C, Ps1, V, Ps),
        unify_value(P, V, Ps, _)
    ).

element_ref(C, Pat, V, PV) :- V = '$c'(C, Pat, PV).

with_arity(Ps0, C, K, Ps) :-
    tuple_shape(K, Shape),
    with_shape(Ps0, C, Shape, Ps).

with_shape([], _, _, []).
with_shape([I|Is], C, Shape, Ps) :-
    arg(I, C, V),
    (   subsumes_term(Shape, V), V \== '$undef', V \== '$u' -> Ps = [I|Ps1] ; Ps = Ps1 ),
    with_shape(Is, C, Shape, Ps1).

%   tuple_shape(+K, -Shape): (_, ..., _) of K elements (the last any term).
tuple_shape(1, _) :- !.
tuple_shape(K, (_, S)) :- K1 is K-1, tuple_shape(K1, S).

with_value([], _, _, []).
with_value([I|Is], C, P, Ps) :-
    arg(I, C, V),
    (   ( V = P -> true ; number(V), number(P), V =:= P ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    with_value(Is, C, P, Ps1).

unifiable_at([], _, _, _, []).
unifiable_at([I|Is], C, Bs, Tmpl, Ps) :-
    arg(I, C, V),
    (   \+ \+ ( bind(Bs, I), Tmpl = V ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    unifiable_at(Is, C, Bs, Tmpl, Ps1).

split_column(C, Ps0, V, Ps) :-
    findall(V0-I, ( member(I, Ps0), arg(I, C, V0) ), Pairs),
    keysort(Pairs, Sorted),
    group_pairs_by_key(Sorted, Groups),
    member(V-Ps, Groups).

%   tuple_of_vars(+P, -Vs): P is a tuple of two or more distinct
%   variables Vs (a pattern such as (X, Y, Z) or (_, _, Z)).
tuple_of_vars(P, [A|Vs]) :-
    nonvar(P), P = (A, B), var(A),
    tuple_vars(B, Vs),
    term_variables(P, All), length(All, K), length([A|Vs], K).

tuple_vars(P, [P]) :- var(P), !.
tuple_vars((A, B), [A|Vs]) :- var(A), tuple_vars(B, Vs).


                 /*******************************
                 *        RANDOM VARIABLES      *
                 *******************************/

%   timed_read(+Read, -X, -TE): the original's current(h), next(h) and
%   prior(h) are h:t, h:t+1 and h:0 (as in ddc.pl).
timed_read(R, X, TE) :-
    nonvar(R),
    (   R = current(X) -> TE = t
    ;   R = next(X) -> TE = t+1
    ;   R = prior(X) -> TE = 0
    ),
    nonvar(X).

%   read_key(+X, +T, +E, +Ps0, -Key, -Entry, -Ps): X's entry at T,
%   computed for the particles of Ps0 that lack it; a non-ground X reads,
%   one branch per key, the keys held at T and the ground heads that
%   clauses h:t (and h:0 at time 0) define at T, as the per-particle
%   engine enumerates them (ddc.pl, read_enum/4); each key is computed for
%   the particles that lack it and read where it is defined.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    ground(X), !,
    value(E, X, T, Ps0, Entry),
    Ps = Ps0.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    env_time_table(E, T, Tab),
    findall(X, tab_match(Tab, X, _), Xs0),
    defined_heads(E, X, T, Ps0, Xs1),
    append(Xs0, Xs1, Xs2), sort(Xs2, Xs),
    member(X, Xs),
    value(E, X, T, Ps0, Entry),
    arg(1, Entry, C),
    defined_at(Ps0, C, Ps),
    Ps \== [].

%   defined_heads(+E, ?X, +T, +Ps, -Keys): the ground instances of X that
%   the bodies of its h:t clauses (h:0 ones at time 0) give at T, when T
%   is the time being computed (h:t+1 clauses were swept at the step);
%   found as sweep_head/6 finds them.
defined_heads(E, X, T, Ps, Keys) :-
    E = env(M, _, _, t(_, _, T1, _), _, _, _),
    T1 == T, !,
    env_now(E, T, ES),
    (   T =:= 0 -> Kinds = [now, zero] ; Kinds = [now] ),
    findall(X1,
            ( member(K, Kinds),
              ( K == zero -> Now is T-1, env_now(E, Now, EK) ; EK = ES ),
              copy_term(X, X1),
              catch(sweep_head(M, K, EK, Ps, X1, _), error(ddc(non_ground_head(_), _), _), fail),
              subsumes_term(X, X1) ),
            Keys).
defined_heads(_, _, _, _, []).

defined_at([], _, []).
defined_at([I|Is], C, Ps) :-
    arg(I, C, V),
    (   ( V == '$u' ; V == '$undef' ) -> Ps = Ps1 ; Ps = [I|Ps1] ),
    defined_at(Is, C, Ps1).

%   unify_read(?P, +Key, +Entry, +Ps0, -Ps): P with the values of Entry
%   (undefined values fail).
unify_read(P, _, Entry, Ps0, Ps) :-
    Entry = e(C, S, _),
    (   S = same(V)
    ->  V \== '$undef',
        unify_value(P, V, Ps0, Ps)
    ;   S == defined
    ->  (   tuple_of_vars(P, _)
        ->  entry_arity(Entry, Arity),
            unify_column(P, C, Arity, Ps0, Ps)
        ;   unify_column(P, C, Ps0, Ps)
        )
    ;   defined_at(Ps0, C, Ps1),
        Ps1 \== [],
        unify_column(P, C, Ps1, Ps)
    ).

%   entry_arity(+Entry, -Arity): the tuple arity every value of a defined
%   entry has (found once), or none.
entry_arity(Entry, Arity) :-
    arg(3, Entry, A0),
    (   A0 \== unknown
    ->  Arity = A0
    ;   arg(1, Entry, C),
        arg(1, C, V1),
        value_arity(V1, 1, K),
        (   K > 1, functor(C, _, N), with_arity_all(N, C, K) -> A = K ; A = none ),
        nb_setarg(3, Entry, A),
        Arity = A
    ).

with_arity_all(N, C, K) :-
    tuple_shape(K, Shape),
    forall(between(1, N, I), ( arg(I, C, V), subsumes_term(Shape, V) )).

value_arity(V, K0, K) :-
    (   nonvar(V), V = (_, B) -> K1 is K0+1, value_arity(B, K1, K) ; K = K0 ).

%   value(+E, +X, +T, +Ps, -Entry): X's entry at T with a value (or
%   '$undef') for every particle of Ps.
value(E, X, T, Ps, Entry) :-
    env_time_table(E, T, Tab),
    (   tab_get(Tab, X, Entry0)
    ->  true
    ;   E = env(_, N, _, _, _, _, _),
        new_column(N, '$u', C0),
        tab_put(Tab, X, e(C0, open, unknown)),
        tab_get(Tab, X, Entry0)
    ),
    Entry = Entry0,
    (   arg(2, Entry, open), E = env(_, _, _, t(_, _, T, _), _, _, _)
    ->  arg(1, Entry, C),
        uncomputed(Ps, C, Miss),
        (   Miss == [] -> true ; compute(E, X, T, Miss, C) ),
        settle(Entry)
    ;   true
    ).

uncomputed([], _, []).
uncomputed([I|Is], C, Ps) :-
    arg(I, C, V),
    (   V == '$u' -> Ps = [I|Ps1] ; Ps = Ps1 ),
    uncomputed(Is, C, Ps1).

%   settle(+Entry): its status once every particle has a value.
settle(Entry) :-
    arg(1, Entry, C),
    functor(C, _, N),
    arg(1, C, V1),
    column_status(N, C, V1, same, S0),
    (   S0 == open -> true
    ;   S0 == same -> nb_setarg(2, Entry, same(V1))
    ;   nb_setarg(2, Entry, S0)
    ).

%   column_status(+I, +C, +V1, +S0, -S): the status of C's arguments I..1
%   (open as soon as one lacks its value).
column_status(0, _, _, S, S) :- !.
column_status(I, C, V1, S0, S) :-
    arg(I, C, V),
    (   V == '$u' -> S = open
    ;   (   S0 == same, V == V1 -> S1 = same
        ;   S0 == mixed -> S1 = mixed
        ;   V == '$undef' -> S1 = mixed
        ;   V1 == '$undef' -> S1 = mixed
        ;   S1 = defined
        ),
        I1 is I-1,
        column_status(I1, C, V1, S1, S)
    ).

%   compute(+E, +X, +T, +Ps, +C): the first applicable clause's draw for
%   each particle of Ps ('$undef' where none applies).
compute(E, X, T, Ps, C) :-
    E = env(M, _, _, _, _, _, _),
    (   T =:= 0 -> K = zero ; K = next ),
    Now is T-1,
    env_now(E, Now, EK),
    env_now(E, T, ES),
    findall(c(K, D, B, At), rv_clause(M, X, K, D, B, At), Cls1),  % (no env: a copy)
    findall(c(now, D, B, At), rv_clause(M, X, now, D, B, At), Cls2),
    append(Cls1, Cls2, Cls),
    assign_clauses(Cls, EK, ES, X, T, Ps, C, Rest),
    set_each(Rest, C, '$undef').

%   assign_clauses(+Clauses, +EK, +ES, +X, +T, +Ps, +C, -Rest): each
%   clause over the particles no earlier one gave a value (Rest: those none
%   did); EK the env of the h:0/h:t+1 clauses' bodies, ES of the h:t ones.
assign_clauses([], _, _, _, _, Ps, _, Ps).
assign_clauses([c(K, D, B, At)|Cls], EK, ES, X, T, Ps, C, Rest) :-
    (   Ps == []
    ->  Rest = []
    ;   ( K == now -> E = ES ; E = EK ),
        Any = any(false),
        assign_clause(E, X, T, K, B, D, At, Ps, C, Any),
        (   arg(1, Any, true) -> uncomputed(Ps, C, Ps1) ; Ps1 = Ps ),   % (nothing given)
        assign_clauses(Cls, EK, ES, X, T, Ps1, C, Rest)
    ).

%   rv_clause(+M, ?X, ?K, -D, -B, -At): a clause of X (a called clause is
%   a fresh copy; calling with X lets the clause index find X's clauses
%   without looking at every random variable's).
rv_clause(M, X, K, D, B, At) :-
    M:'$b_rv'(X, K, D, B, At).

%   A distribution error names the clause (file:line), as in ddc.pl.  The
%   particles of the env's check list that this clause gave a value are
%   checked for a later clause that also applies (check_rivals/8).
assign_clause(E, X, T, K, B, D, At, Rest, C, Any) :-
    run_clause(E, X, T, K, B, At, Rest, C, assign_branch(Any, C, D)).

assign_branch(Any, C, D, Ps) :-
    nb_setarg(1, Any, true),
    assign(Ps, C, D).

%   run_clause(+E, +X, +T, +K, +B, +At, +Rest, +C, :Action): Action on the
%   particles of each branch of body B over Rest; a distribution error
%   names the clause's line; then the particles of the env's check list
%   that got a value in C are checked for a later clause that applies too.
run_clause(E, X, T, K, B, At, Rest, C, Action) :-
    At = at(L, Id, R),
    E = env(M, _, _, _, _, _, Check),
    catch(forall(beval(B, E, Rest, Ps), call(Action, Ps)), Err, clause_error(Err, M:L)),
    (   R == true, Check \== []
    ->  ord_intersection(Rest, Check, Watched),
        exclude(uncomputed_at(C), Watched, Given),
        check_rivals(Given, E, X, T, K, Id, L)
    ;   true
    ).

uncomputed_at(C, I) :- arg(I, C, V), V == '$u'.

%   clause_error(+Error, +Where): an error raised in the body of the clause
%   at Where is the program's error there, as the per-particle engine
%   reports it (ddc.pl, program_error/4): a distribution error, any other
%   Prolog error or a term the program threw; the engine's own errors (which
%   name their clause) pass unchanged.
clause_error(error(ddc(Cause, W), _), Where) :-
    var(W), !,
    throw(error(ddc(Cause, Where), _)).
clause_error(error(ddc_distribution(D, Why), _), Where) :- !,
    throw(error(ddc(distribution(D, Why), Where), _)).
clause_error(E, _) :-
    ddc:engine_error(E), !,
    throw(E).
clause_error(E, Where) :-
    throw(error(ddc(prolog_error(E), Where), _)).

%   check_rivals(+Ps, +E, +X, +T, +K, +Id, +L): no clause of kind K after
%   clause Id applies to X in the particles Ps (those an earlier one gave
%   X's value); else error overlapping_clauses, at this clause's line.
check_rivals([], _, _, _, _, _, _) :- !.
check_rivals(Ps, E, X, T, K, Id, L) :-
    E = env(M, _, _, _, _, _, _),
    (   M:'$b_rv'(X, K, _, B, at(L2, Id2, _)), Id2 > Id,
        \+ \+ beval(B, E, Ps, _)
    ->  throw(error(ddc(overlapping_clauses(X:T, M:L2), M:L), _))
    ;   true
    ).

assign(_, _, D) :-
    var(D), !,
    throw(error(ddc(unbound_distribution, _), _)).      % clause_error/2 names the clause
assign(Ps, C, D) :-
    (   D = val(V), \+ has_col(V)
    ->  set_each(Ps, C, V)
    ;   D = val(V)
    ->  plan(V, Tmpl, Bs),
        (   Ps = [_, _, _, _, _, _, _, _, _, _, _, _, _, _, _, _|_]
        ->  compiled_instance(Ps, Bs, Tmpl, C)
        ;   instance_each(Ps, Bs, Tmpl, C)
        )
    ;   plan(D, Tmpl, Bs),
        dist_prepare(Tmpl, P),
        draw_each(Ps, Bs, P, C)
    ).

set_each([], _, _).
set_each([I|Is], C, V) :-
    (   arg(I, C, U), U == '$u' -> nb_setarg(I, C, V) ; true ),
    set_each(Is, C, V).

instance_each([], _, _, _).
instance_each([I|Is], Bs, Tmpl, C) :-
    (   arg(I, C, U), U == '$u'
    ->  \+ \+ ( bind(Bs, I), nb_setarg(I, C, Tmpl) )
    ;   true
    ),
    instance_each(Is, Bs, Tmpl, C).

%   (With one column to bind, the common case, a loop that binds it
%   directly: bind/2's list walk costs as much as a draw's arithmetic.)
%   (And when that column's value is the mean itself, as in gaussian([X, Y,
%   Z], Cov) := pos(O):t ~= (X, Y, Z), not even that: the value is passed.)
draw_each(Ps, [C1-Pat], P, C) :-
    dist_mean_slots(P, Slots), Slots == Pat, !,
    draw_at(Ps, C1, P, C).
draw_each(Ps, [C1-Pat], P, C) :- !,
    draw_each1(Ps, C1, Pat, P, C).
draw_each([], _, _, _).
draw_each([I|Is], Bs, P, C) :-
    (   arg(I, C, U), U == '$u'
    ->  \+ \+ ( bind(Bs, I), dist_sample_prepared(P, S), nb_setarg(I, C, S) )
    ;   true
    ),
    draw_each(Is, Bs, P, C).

draw_at([], _, _, _).
draw_at([I|Is], C1, P, C) :-
    (   arg(I, C, U), U == '$u'
    ->  arg(I, C1, Mean),
        dist_sample_at(P, Mean, S),
        nb_setarg(I, C, S)
    ;   true
    ),
    draw_at(Is, C1, P, C).

draw_each1([], _, _, _, _).
draw_each1([I|Is], C1, Pat, P, C) :-
    (   arg(I, C, U), U == '$u'
    ->  \+ \+ ( arg(I, C1, Pat), dist_sample_prepared(P, S), nb_setarg(I, C, S) )
    ;   true
    ),
    draw_each1(Is, C1, Pat, P, C).

%   derived(+G, +T, +E, +Ps0, -Ps): G at time T: from the instances
%   materialised at T (a predicate a transition body reads at t: each
%   group of particles with the same instances a branch per instance),
%   else by its clauses (each solution a branch).
derived(G, T, E, Ps0, Ps) :-
    E = env(M, _, _, _, _, _, _),
    functor(G, N, A),
    M:'$b_lookback'(N/A),
    env_time_table(E, T, Tab),
    tab_get(Tab, '$inst'(N/A), e(C, S, _)),
    !,
    (   S = same(L)
    ->  Ps = Ps0
    ;   split_column(C, Ps0, L, Ps)
    ),
    member(G, L).
derived(G, T, E, Ps0, Ps) :-
    E = env(M, _, _, _, _, _, _),
    (   T =:= 0 -> K = zero, Now = 0 ; K = next, Now is T-1 ),
    (   M:'$b_der'(H, K, B0, L), Now1 = Now
    ;   M:'$b_der'(H, now, B0, L), Now1 = T
    ),
    copy_term(H-B0, G1-B),
    G1 = G,
    env_now(E, Now1, E1),
    catch(beval(B, E1, Ps0, Ps), Err, clause_error(Err, M:L)),
    (   has_free_var(G)                 % not range-restricted: as ddc.pl, an error
    ->  throw(error(ddc(non_ground_head(G), M:L), _))
    ;   true
    ).

                 /*******************************
                 *            FILTER            *
                 *******************************/

%!  batch_new(+Module, +Items, +N, +Seed, +Threads, -State) is det.
%
%   N particles at time 0 of the program Items (ddc.pl's classified
%   clauses, already loaded into Module, in the fragment: see
%   batch_check_program/2): every h:0 clause's ground heads drawn.
%   Threads > 1: the particles are split into that many contiguous groups
%   (sizes differing by at most one), each with a random stream of its own
%   (the first seeded with Seed, the others with seeds drawn from it), whose
%   steps run at the same time in as many threads (see "Groups" below).
%   The particles depend on Seed and Threads, not on the machine.
batch_new(M, Items, N, Seed, K0, State) :-
    compile(M, Items),
    K is min(K0, N),                    % (no empty group)
    (   K =:= 1
    ->  new_group(M, N, Seed, true, State)
    ;   K1 is K-1,
        length(Seeds, K1),
        random_property(state(Saved)),
        call_cleanup(( set_random(seed(Seed)),
                       maplist(random_between(0, 0x3fffffffffffffff), Seeds) ),
                     set_random(state(Saved))),
        group_sizes(N, K, Sizes),
        length(NoChecks, K1), maplist(=(false), NoChecks),
        maplist(new_group(M), Sizes, [Seed|Seeds], [true|NoChecks], Gs),
        State = groups(Gs)
    ).

group_sizes(N, K, Sizes) :-
    findall(S, ( between(1, K, G), S is (N*G)//K - (N*(G-1))//K ), Sizes).

%   Overlapping clauses are looked for in the first 20 particles (of the
%   first group), as the per-particle filter does at every step.
new_group(M, N, Seed, Check, State) :-
    check_list(Check, N, Ck),
    random_property(state(Saved)),
    call_cleanup(
        ( set_random(seed(Seed)),
          tab_new(Tab0), tab_new(Tab),
          E = env(M, N, -1, t(-1, Tab0, 0, Tab), [], [], Ck),
          numlist(1, N, All),
          sweep(M, zero, E, 0, All),
          materialise_derived(M, E, 0, All),
          random_property(state(R)) ),
        set_random(state(Saved))),
    State = bs(M, N, 0, t(-1, Tab0, 0, Tab), [], R).

%   materialise_derived(+M, +E, +T, +All): each lookback predicate's
%   instances at T, per particle (a list without repeats, in the order
%   its clauses give them), as the entry '$inst'(N/A) of T's table.
materialise_derived(M, E, T, All) :-
    forall(M:'$b_lookback'(N/A),
           (   functor(G, N, A),
               Now is T-1,
               env_now(E, Now, E1),
               env_time_table(E, T, Tab),
               E = env(_, Size, _, _, _, _, _),
               collect(G, G:(t+1), L, E1, All, _),
               functor(C, c, Size),
               (   L = '$c'(LC, _, _)
               ->  sets_each(All, LC, C)
               ;   list_to_set(L, Set), fill(Size, C, Set)
               ),
               tab_put(Tab, '$inst'(N/A), e(C, open, none)),
               tab_get(Tab, '$inst'(N/A), Entry),
               settle(Entry)
           )).

sets_each([], _, _).
sets_each([I|Is], LC, C) :-
    arg(I, LC, L), list_to_set(L, Set), arg(I, C, Set),
    sets_each(Is, LC, C).

%   sweep(+M, +Kind, +E, +T, +All): every ground head of a Kind clause
%   drawn at T for the particles that have it.  The heads come from the
%   goals the clause's body starts with: static goals, derived atoms
%   (pos(A):t+1 := hidden(A):t+1, ...: the per-particle filter's sweep
%   proves the whole body), and reads at t, whose keys are those held (so
%   a value held at t that a persistence clause such as h:t+1 ~ val(V) :=
%   h:t ~= V carries on is carried on in the particles that hold it).
sweep(M, K, E, T, All) :-
    findall(X-Ps, sweep_head(M, K, E, All, X, Ps), Pairs0),
    keysort(Pairs0, Pairs),
    group_pairs_by_key(Pairs, Groups),
    forall(member(X-Pss, Groups),
           (   memberchk(all, Pss) -> value(E, X, T, All, _)
           ;   ord_union(Pss, Ps), value(E, X, T, Ps, _)
           )).

%   (Ps is all when the prefix is static: every particle.  A head whose
%   key reads a column, x(K):t+1 := k:t ~= K, ..., gives a key per group
%   of particles with the same value.)
%   A head the whole body leaves non-ground is an error, as in ddc.pl (a
%   prefix that is not the whole body may leave it to the rest).
sweep_head(M, K, E, All, X, Ps) :-
    M:'$b_rv'(H, K, _, B, at(L, _, _)), H \= observation(_),
    copy_term(H-B, X0-B1),
    sweep_prefix(B1, M, P),
    (   static_conj(P, M)
    ->  prefix_solutions(P, E), Ps = all, X = X0
    ;   beval(P, E, All, Ps0),
        split(X0, Ps0, X, Ps)
    ),
    (   ground(X)
    ->  true
    ;   P == B1
    ->  throw(error(ddc(non_ground_head(X), M:L), _))
    ;   fail
    ).

static_conj(true, _) :- !.
static_conj((A, B), M) :- !, static_goal(A, M), static_conj(B, M).
static_conj(A, M) :- static_goal(A, M).

prefix_solutions(true, _) :- !.
prefix_solutions((A, B), E) :- !, call_static(A, E), prefix_solutions(B, E).
prefix_solutions(A, E) :- call_static(A, E).

sweep_prefix((A, B), M, P) :- !,
    (   sweep_goal(A, M) -> P = (A, P1), sweep_prefix(B, M, P1) ; P = true ).
sweep_prefix(A, M, P) :-
    (   sweep_goal(A, M) -> P = A ; P = true ).

sweep_goal(G, M) :-
    (   nonvar(G), G = (_:TE ~= _) -> TE == t
    ;   nonvar(G), G = (D:_), callable(D) -> true        % a derived atom (hidden(A):t+1)
    ;   static_goal(G, M)
    ).

static_goal(G, M) :-
    callable(G), G \= _:_, G \= (_ ~= _), G \= (_, _), G \= (_ ; _), G \= (_ -> _),
    G \= (\+ _), G \= findall(_, _, _), G \= findall_forward(_, _, _),
    G \= (_ is _), \+ test_goal(G),
    (   M:'$b_static_pred'(G, _) -> true
    ;   model_goal(G) -> true
    ;   \+ visible(M, G)                              % a fact of the step
    ).

%!  batch_step(+State0, +Observations, +Facts, -Result) is det.
%
%   Result = step(State, LogWeights): every particle advanced from t to
%   t+1 with the Facts (actions and plain observations) of t+1 and
%   weighted by the Observations (terms H ~= V).  State0 is not changed.
batch_step(groups([G1|Gs]), Obs, Facts, step(groups([S1|Ss]), LWs)) :- !,
    length(Gs, K1),
    numlist(1, K1, Tags),
    message_queue_create(Q),
    setup_call_cleanup(
        maplist(start_step(Q, Obs, Facts), Tags, Gs),
        (   catch(group_step(G1, Obs, Facts, true, step(S10, LWs1)), E, true),
            maplist(step_result(Q), Tags, Results)
        ),
        message_queue_destroy(Q)),
    (   nonvar(E) -> throw(E) ; true ),
    maplist(group_done(Facts), Gs, Results, Ss, LWss),
    S1 = S10,
    append([LWs1|LWss], LWs).
batch_step(State0, Obs, Facts, Result) :-
    group_step(State0, Obs, Facts, true, Result).

%!  overlap_checked_particles(-N) is det.
%
%   Overlapping clauses are looked for in the first N particles of every
%   filter step, by both engines (ddc_filter.pl's step_range_at/10 too).
overlap_checked_particles(20).

check_list(true, N, Ck) :- !,
    overlap_checked_particles(K0), K is min(N, K0), numlist(1, K, Ck).
check_list(false, _, []).

%   group_step(+State0, +Obs, +Facts, +Check, -Result): batch_step/4 of
%   one group; Check: whether its first particles are checked for
%   overlapping clauses (the first group's).
group_step(State0, Obs, Facts, Check, step(State, LWs)) :-
    State0 = bs(M, N, T, t(_, _, _, Tab), _, R0),
    check_list(Check, N, Ck),
    T1 is T+1,
    tab_new(Tab1),
    findall(H-V, member(H ~= V, Obs), HVs),
    E = env(M, N, T, t(T, Tab, T1, Tab1), Facts, HVs, Ck),
    numlist(1, N, All),
    random_property(state(Saved)),
    call_cleanup(
        ( set_random(state(R0)),
          new_column(N, 0.0, LW),
          forall(member(H-V, HVs), weigh_observation(E, H, V, All, LW)),
          sweep(M, next, E, T1, All),
          materialise_derived(M, E, T1, All),
          random_property(state(R)) ),
        set_random(state(Saved))),
    LW =.. [_|LWs],
    duplicate_term(Facts, Facts1),
    State = bs(M, N, T1, t(T, Tab, T1, Tab1), Facts1, R).

%   weigh_observation(+E, +H, +V, +Ps, +LW): the log density of V under
%   H's first applicable clause at t+1, added to each particle's LW.
weigh_observation(E, H, V, Ps, LW) :-
    E = env(M, N, T, _, _, _, _),
    T1 is T+1,
    new_column(N, '$u', Done),
    forall(rv_clause(M, H, next, D, B, At),
           weigh_clause(E, H, T1, next, B, D, At, V, Ps, Done, LW)),
    env_now(E, T1, ES),
    forall(rv_clause(M, H, now, D, B, At),
           weigh_clause(ES, H, T1, now, B, D, At, V, Ps, Done, LW)),
    (   member(I, Ps), arg(I, Done, U), U == '$u'
    ->  throw(error(ddc(no_observation_clause(H ~= V), query), _))
    ;   true
    ).

%   (A distribution error names the clause; overlaps are checked as for
%   draws: run_clause/9.)
weigh_clause(E, H, T, K, B, D, At, V, Ps, Done, LW) :-
    uncomputed(Ps, Done, Rest),
    (   Rest == [] -> true
    ;   run_clause(E, H, T, K, B, At, Rest, Done, weigh_branch(D, V, Done, LW))
    ).

weigh_branch(D, _, _, _, _) :-
    var(D), !,
    throw(error(ddc(unbound_distribution, _), _)).
weigh_branch(D, V, Done, LW, Ps) :-
    plan(D, Tmpl, Bs),
    dist_prepare(Tmpl, P),
    weigh_each(Ps, Bs, P, V, Done, LW).

weigh_each(Ps, [C1-Pat], P, V, Done, LW) :-
    dist_mean_slots(P, Slots), Slots == Pat, !,
    weigh_at(Ps, C1, P, V, Done, LW).
weigh_each(Ps, [C1-Pat], P, V, Done, LW) :- !,
    weigh_each1(Ps, C1, Pat, P, V, Done, LW).
weigh_each([], _, _, _, _, _).
weigh_each([I|Is], Bs, P, V, Done, LW) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), dist_log_density_prepared(P, V, LP), add_log(I, LW, LP) )
    ;   true
    ),
    weigh_each(Is, Bs, P, V, Done, LW).

weigh_at([], _, _, _, _, _).
weigh_at([I|Is], C1, P, V, Done, LW) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        arg(I, C1, Mean),
        dist_log_density_at(P, Mean, V, LP),
        add_log(I, LW, LP)
    ;   true
    ),
    weigh_at(Is, C1, P, V, Done, LW).

weigh_each1([], _, _, _, _, _, _).
weigh_each1([I|Is], C1, Pat, P, V, Done, LW) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        \+ \+ ( arg(I, C1, Pat), dist_log_density_prepared(P, V, LP), add_log(I, LW, LP) )
    ;   true
    ),
    weigh_each1(Is, C1, Pat, P, V, Done, LW).

add_log(I, LW, LP) :-
    arg(I, LW, L0),
    (   L0 > -1.0e308, LP > -1.0e308
    ->  L is L0 + LP, nb_setarg(I, LW, L)
    ;   minus_infinity(L0) -> true
    ;   nb_setarg(I, LW, LP)
    ).

minus_infinity(X) :- float(X), X < -1.0e308.

%!  batch_resample(+State0, +Indices, -State) is det.
%
%   Particle i (1-based position in Indices) becomes a copy of particle
%   Indices[i] (0-based).  The latest time's columns are resampled now,
%   the previous time's when a query first reads them (pending/2).  Each
%   group keeps its random stream.
batch_resample(S0, Is0, S) :-
    state_groups(S0, Gs0),
    maplist(batch_size, Gs0, Sizes),
    maplist(latest_table, Gs0, Src1),
    maplist(older_table, Gs0, Src0),
    sources(Is0, Sizes, Pairs),
    maplist(resampled_group(Src0, Src1), Gs0, Pairs, Gs),
    (   S0 = groups(_) -> S = groups(Gs) ; Gs = [S] ).

state_groups(groups(Gs), Gs) :- !.
state_groups(S, [S]).

latest_table(bs(_, _, _, t(_, _, _, Tab), _, _), Tab).
older_table(bs(_, _, _, t(_, Tab, _, _), _, _), Tab).

%   sources(+Indices, +Sizes, -Pairs): for each group (of Sizes), its
%   particles' ancestors as Group-Index pairs (1-based).
sources(Is, Sizes, Pairs) :-
    maplist(source(Sizes), Is, All),
    split_by(Sizes, All, Pairs).

source(Sizes, J, G-L) :- source(Sizes, 1, J, G, L).
source([Size|Sizes], G0, J, G, L) :-
    (   J < Size -> G = G0, L is J+1
    ;   J1 is J-Size, G1 is G0+1, source(Sizes, G1, J1, G, L)
    ).

split_by([], [], []).
split_by([Size|Sizes], All, [P|Ps]) :-
    length(P, Size),
    append(P, Rest, All),
    split_by(Sizes, Rest, Ps).

resampled_group(Src0, Src1, bs(M, Size, T, t(T0, _, T1, _), Fs, R), Pairs,
                bs(M, Size, T, t(T0, pending(Src0, Pairs), T1, New1), Fs, R)) :-
    resample_tables(Src1, Pairs, New1).

%   resample_tables(+Sources, +Pairs, -New): a table of the particles Pairs
%   (Group-Index) of the tables Sources (one per group; a key a group lacks
%   is '$u' there: never drawn in those particles).
resample_tables(Srcs0, Pairs, New) :-
    maplist(real_table, Srcs0, Srcs),
    tab_new(New),
    findall(K, ( member(Tab, Srcs), Tab \== none, tab_match(Tab, K, _) ), Ks0),
    sort(Ks0, Ks),
    length(Pairs, N),
    forall(member(K, Ks),
           (   maplist(source_entry(K), Srcs, Es),
               resampled_entry(Es, Pairs, N, E),
               tab_link(New, K, E)
           )).

source_entry(K, Tab, E) :-
    (   Tab \== none, tab_get(Tab, K, E0) -> E = E0 ; E = none ).

%   (A column of one value is the same after resampling: a source's of the
%   same length is shared, not copied: a complete column is never written.)
resampled_entry(Es, Pairs, N, E) :-
    (   Es = [e(_, same(V), A)|_], forall(member(E1, Es), same_entry(E1, V))
    ->  (   member(e(C0, _, _), Es), functor(C0, _, N)
        ->  C1 = C0
        ;   functor(C, c, N), fill(N, C, V), duplicate_term(C, C1)
        ),
        E = e(C1, same(V), A)
    ;   maplist(entry_column, Es, Cs),
        Src =.. [s|Cs],
        pair_values(Pairs, Src, Vs),
        C =.. [c|Vs],
        (   forall(member(E1, Es), defined_entry(E1))
        ->  common_arity(Es, A),
            E = e(C, defined, A)
        ;   E0 = e(C, open, unknown),
            duplicate_term(E0, E),
            settle(E)
        )
    ).

same_entry(E, V) :- nonvar(E), E = e(_, same(V1), _), V1 == V.

%   defined_entry(+E): E is a group's entry with a value in every particle
%   (a group that lacks the key, none, has it open: never drawn there).
defined_entry(E) :- E \== none, arg(2, E, defined).

entry_column(none, '$none') :- !.
entry_column(e(C, _, _), C).

pair_values([], _, []).
pair_values([G-L|Ps], Src, [V|Vs]) :-
    arg(G, Src, C),
    (   C == '$none' -> V = '$u' ; arg(L, C, V) ),
    pair_values(Ps, Src, Vs).

common_arity([e(_, _, A)|Es], Arity) :-
    (   forall(member(e(_, _, A1), Es), A1 == A) -> Arity = A ; Arity = unknown ).

%   real_table(+Tab0, -Tab): a pending table resampled.
real_table(pending(Srcs, Pairs), Tab) :- !,
    resample_tables(Srcs, Pairs, Tab).
real_table(Tab, Tab).

%!  batch_keep(+State, -Kept) is det.
%
%   Kept is State's skeleton assembled anew by non-backtrackable
%   assignment (nb_linkarg/3), sharing State's tables, facts and streams:
%   a term a filter may keep linked in a global variable across queries.
%   (A state is made by unification; a binding made while a choice point
%   was newer than the variable is undone by backtracking to it, even
%   after the term is linked, e.g. when the query that made it ends.  The
%   tables and columns are made by non-backtrackable assignment already.)
batch_keep(groups(Gs), Kept) :- !,
    maplist(batch_keep, Gs, Ks),
    kept_list(Ks, L),
    functor(Kept, groups, 1),
    nb_linkarg(1, Kept, L).
batch_keep(bs(M, N, T, t(T0, Tab0, T1, Tab1), Fs, R), Kept) :-
    functor(TT, t, 4),
    nb_setarg(1, TT, T0), nb_linkarg(2, TT, Tab0),
    nb_setarg(3, TT, T1), nb_linkarg(4, TT, Tab1),
    functor(Kept, bs, 6),
    nb_setarg(1, Kept, M), nb_setarg(2, Kept, N), nb_setarg(3, Kept, T),
    nb_linkarg(4, Kept, TT), nb_linkarg(5, Kept, Fs), nb_linkarg(6, Kept, R).

kept_list([], []).
kept_list([X|Xs], L) :-
    kept_list(Xs, L1),
    functor(L, '[|]', 2),
    nb_linkarg(1, L, X),
    nb_linkarg(2, L, L1).

%!  batch_module(+State, -Module) is det.
%
%   The module the state's program is loaded into.
batch_module(groups([G|_]), M) :- !, batch_module(G, M).
batch_module(bs(M, _, _, _, _, _), M).

%!  batch_time(+State, -T) is det.
batch_time(groups([G|_]), T) :- !, batch_time(G, T).
batch_time(bs(_, _, T, _, _, _), T).

%!  batch_size(+State, -N) is det.
batch_size(groups(Gs), N) :- !, foldl(add_size, Gs, 0, N).
batch_size(bs(_, N, _, _, _, _), N).

add_size(G, N0, N) :- batch_size(G, K), N is N0+K.

%!  batch_holds(+State, +Goal, -Flags) is det.
%
%   Flags: for each particle 1 if Goal holds at the current time (t is the
%   current time), else 0.  Values the goal needs and a particle lacks are
%   drawn and kept (the state's columns are updated in place).
batch_holds(groups(Gs), Goal, Flags) :- !,
    maplist(group_holds(Goal), Gs, Fss),
    append(Fss, Flags).
batch_holds(S, Goal, Flags) :-
    query_env(S, E, All),
    with_state(S, branch_union(Goal, E, All, Ps)),
    S = bs(_, N, _, _, _, _),
    flags(1, N, Ps, Flags).

%   (Each group's query on a copy of the goal: its bindings are its own.)
group_holds(Goal, G, Flags) :-
    copy_term(Goal, Goal1),
    batch_holds(G, Goal1, Flags).

flags(I, N, _, []) :- I > N, !.
flags(I, N, [I|Ps], [1|Fs]) :- !, I1 is I+1, flags(I1, N, Ps, Fs).
flags(I, N, Ps, [0|Fs]) :- I1 is I+1, flags(I1, N, Ps, Fs).

%!  batch_values(+State, +Template, +Goal, -Values) is det.
%
%   Values: for each particle Template at Goal's first solution of its own,
%   or the atom none.
batch_values(groups(Gs), Template, Goal, Values) :- !,
    maplist(group_values(Template-Goal), Gs, Vss),
    append(Vss, Values).
batch_values(S, Template, R0 ~= V, Values) :-
    timed_read(R0, X, TE), !,
    batch_values(S, Template, X:TE ~= V, Values).
batch_values(S, Template, Goal, Values) :-          % a variable's values: read as they are
    nonvar(Goal), Goal = (X:TE ~= V), var(V), ground(X),
    (   Template == V -> Wrap = plain ; Template == value(V) -> Wrap = value ),
    !,
    query_env(S, E, All),
    read_time(TE, E, T),
    (   env_time_table(E, T, _)
    ->  with_state(S, value(E, X, T, All, Entry)),
        arg(1, Entry, C),
        C =.. [_|Vs],
        maplist(wrapped_value(Wrap), Vs, Values)
    ;   S = bs(_, N, _, _, _, _),
        length(Values, N), maplist(=(none), Values)
    ).
batch_values(S, Template, Goal, Values) :-
    query_env(S, E, All),
    S = bs(_, N, _, _, _, _),
    new_column(N, none, VC),
    new_column(N, '$u', Done),
    with_state(S, forall(beval(Goal, E, All, Ps),
                         ( plan(Template, Tmpl, Bs), value_each(Ps, Bs, Tmpl, Done, VC) ))),
    VC =.. [_|Values].

wrapped_value(Wrap, V, W) :-
    (   ( V == '$undef' ; V == '$u' ) -> W = none
    ;   Wrap == value -> W = value(V)
    ;   W = V
    ).

group_values(TG, G, Values) :-
    copy_term(TG, Template-Goal),
    batch_values(G, Template, Goal, Values).

value_each([], _, _, _, _).
value_each([I|Is], Bs, Tmpl, Done, VC) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), nb_setarg(I, VC, Tmpl) )
    ;   true
    ),
    value_each(Is, Bs, Tmpl, Done, VC).

query_env(bs(M, N, T, Tabs, Fs, _), env(M, N, T, Tabs, Fs, [], []), All) :-
    numlist(1, N, All).

%   with_state(+State, :Goal): Goal (a query) draws what it needs from
%   State's random stream, which goes on from there (in place: State is
%   the filter's own term).
with_state(S, Goal) :-
    arg(6, S, R0),
    random_property(state(Saved)),
    call_cleanup(( set_random(state(R0)), Goal, random_property(state(R1)) ),
                 set_random(state(Saved))),
    nb_setarg(6, S, R1).

                 /*******************************
                 *            GROUPS            *
                 *******************************/

%   A filter of K > 1 groups is groups([S1, ..., SK]), each Si a filter
%   state of its own particles (contiguous: S1's first, ...).  A step
%   steps S1 in the calling thread and each other group in a worker thread
%   (kept for the life of the process, shared by all filters), which gets a
%   copy of the group's latest table only (a step reads no older one) and
%   sends back the stepped group.  Resampling joins the groups into one
%   state, resamples it and splits it again (each group keeps its stream);
%   queries ask each group in turn.

start_step(Q, Obs, Facts, Tag, G) :-
    G = bs(M, N, T, t(_, _, T, Tab), Fs, R),
    batch_worker(Tag, Thread),
    thread_send_message(Thread, step_job(Q, Tag, bs(M, N, T, t(none, none, T, Tab), Fs, R),
                                         Obs, Facts)).

step_result(Q, Tag, Out) :-
    thread_get_message(Q, Tag-Out).

%   A worker sends back only what is new: the table of t+1, the weights
%   and its stream; the group's table of t is the one this thread holds.
group_done(Facts, G, done(T1, Tab1, R, LWs), S, LWs) :- !,
    G = bs(M, N, T, t(_, _, _, Tab), _, _),
    duplicate_term(Facts, Facts1),
    S = bs(M, N, T1, t(T, Tab, T1, Tab1), Facts1, R).
group_done(_, _, error(E), _, _) :- throw(E).

%   batch_worker(+Tag, -Alias): the worker thread for groups Tag.
batch_worker(Tag, Alias) :-
    atom_concat('$ddc_batch_worker_', Tag, Alias),
    with_mutex('$ddc_batch_workers',
               (   catch(thread_property(Alias, status(running)), _, fail)
               ->  true
               ;   thread_create(worker_loop, _, [alias(Alias), detached(true)])
               )).

worker_loop :-
    thread_get_message(Job),
    (   Job = step_job(Q, Tag, S0, Obs, Facts)
    ->  catch(( group_step(S0, Obs, Facts, false, step(S, LWs)),
                S = bs(_, _, T1, t(_, _, _, Tab1), _, R),
                Out = done(T1, Tab1, R, LWs) ),
              E, Out = error(E)),
        catch(thread_send_message(Q, Tag-Out), _, true)
    ;   true
    ),
    worker_loop.
