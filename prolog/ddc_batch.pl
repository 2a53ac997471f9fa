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
    time t for queries and drops t-1.  Differences, documented in the
    README: clauses are tried in order over the particles without the
    overlap check (a later clause that also applies is not an error), and
    the random draws come in another order (clause by clause over the
    particles), so the same seed gives other particles than the
    per-particle engine.

    Fragment (batch_check_program/2 names the first clause outside it,
    file:line): random variables h:0, h:t+1 and h:t; derived atoms h:t+1
    and h:t read at t+1 or in queries (not read at t in a transition body:
    those the per-particle engine materialises); static predicates (facts,
    plain Prolog clauses, untimed derived atoms with static bodies), the
    step's facts (actions, plain observations); bodies of conjunctions,
    \+, if-then-else, disjunction, reads h:t ~= P, h:t+1 ~= P, h:0 ~= P,
    untimed reads of an observation of the step, is/2, comparisons, ==,
    \==, =, findall/3 and findall_forward/3, calls of static predicates and
    of Prolog's builtins.
*/

:- module(ddc_batch,
          [ batch_check_program/2,      % +Items, +File
            batch_new/6,                % +Module, +Items, +File, +N, +Seed, -State
            batch_step/4,               % +State0, +Observations, +Facts, -Result
            batch_resample/3,           % +State0, +Indices, -State
            batch_holds/3,              % +State, +Goal, -Flags
            batch_values/4,             % +State, +Template, +Goal, -Values
            batch_time/2,               % +State, -T
            batch_size/2                % +State, -N
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(ddc_dist).

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
%     '$b_rv'(X, Kind, Dist, Body, Line)      Kind: zero, next, now
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
check_body(X ~= _, _, _, F, L) :- !,
    (   nonvar(X), X = observation(_) -> true
    ;   unsupported(F, L, untimed_read(X))
    ).
check_body(G:TE, Is, K, F, L) :- !,
    check_time(G, TE, F, L),
    (   TE == t, K \== state, callable(G), derived_timed(G, Is)
    ->  unsupported(F, L, derived_read_at_t(G))
    ;   true
    ).
check_body(G, _, _, F, L) :-
    compound(G), functor(G, N, A),
    memberchk(N/A, [sample/2, true/1, belief/1, timestep/1, current/1, next/1, prior/1]), !,
    unsupported(F, L, G).
check_body(_, _, _, _, _).

check_time(X, TE, F, L) :-
    (   nonvar(TE), ( TE == t ; TE = T0+1, T0 == t ; TE == 0 ) -> true
    ;   unsupported(F, L, time(X:TE))
    ).

derived_timed(G, Items) :-
    functor(G, N, A), functor(P, N, A),
    memberchk(der(_, P, K, _, _), Items), K \== u.

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
    forall(member(rv(_, X, K, D, B, L), Items),
           ( kind(K, K1), assertz(M:'$b_rv'(X, K1, D, B, L)) )),
    forall(member(der(_, X, K, B, L), Items),
           (   K == u
           ->  assertz(M:'$b_static'(X, B)), static_pred(M, X, derived)
           ;   kind(K, K1), assertz(M:'$b_der'(X, K1, B, L))
           )),
    forall(member(plain(C, _), Items),
           ( clause_head(C, H), callable(H) -> static_pred(M, H, plain) ; true )).

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

%   A table of one time: Key -> e(Column, Status), Status one of
%   open (some particle may lack its value: '$u'), same(V) (every particle
%   holds V, '$undef' where no clause applied), defined (each particle a
%   value of its own), mixed (some undefined).  A fixed number of bucket
%   chains; an entry is copied once, when put, and then updated in place,
%   so that a column taken from the table stays the table's own.
tab_new(T) :- functor(T, tab, 1024).

tab_get(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L), nonvar(L), memberchk(K-E0, L), E = E0.

tab_put(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L),
    duplicate_term(K-E, KE),        % (a term made by unification may be undone)
    (   var(L) -> nb_linkarg(I, T, [KE]) ; nb_linkarg(I, T, [KE|L]) ).

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

%   env(Module, N, Now, Tabs, Facts, Obs): Now is the time that t means in
%   the body being evaluated; Tabs t(T0, Tab0, T1, Tab1) the tables held
%   (T1 the latest: values of T0 are only read, a value T0 lacks is
%   undefined, as in the per-particle filter's frozen time); Facts the
%   facts of the latest time; Obs its observations H-V.
env_time_table(env(_, _, _, t(T0, Tab0, T1, Tab1), _, _), T, Tab) :-
    (   T == T1 -> Tab = Tab1
    ;   T == T0 -> Tab = Tab0
    ).

env_now(env(M, N, _, Tabs, Fs, Os), Now, env(M, N, Now, Tabs, Fs, Os)).

read_time(t, env(_, _, Now, _, _, _), Now) :- !.
read_time(T0+1, env(_, _, Now, _, _, _), T) :- T0 == t, !, T is Now+1.
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
%   all three).

%   plan(+T, -Tmpl, -Binds): Tmpl is T with each '$c'(C, Pattern, V)
%   replaced by V, Binds the C-Pattern pairs (each once): bind/2 makes Tmpl
%   a particle's instance.
plan(T, Tmpl, Binds) :-
    plan(T, Tmpl, [], Binds0),
    reverse(Binds0, Binds).

plan(T, T, Bs, Bs) :- var(T), !.
plan('$c'(C, P, V), V, Bs0, Bs) :- !,
    (   member(C0-P0, Bs0), C0 == C, P0 == P -> Bs = Bs0 ; Bs = [C-P|Bs0] ).
plan(T, T, Bs, Bs) :- atomic(T), !.
plan(T, T1, Bs0, Bs) :-
    compound_name_arguments(T, F, As),
    plan_list(As, As1, Bs0, Bs),
    compound_name_arguments(T1, F, As1).

plan_list([], [], Bs, Bs).
plan_list([A|As], [A1|As1], Bs0, Bs) :-
    plan(A, A1, Bs0, Bs1),
    plan_list(As, As1, Bs1, Bs).

bind([], _).
bind([C-P|Bs], I) :- arg(I, C, P), bind(Bs, I).

col_ref(C, V, '$c'(C, V, V)).

has_col(T) :- compound(T), ( T = '$c'(_, _, _) -> true ; arg(_, T, A), has_col(A) ), !.

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
beval(X ~= P, E, Ps0, Ps) :- !,                   % an observation of the step
    split(X, Ps0, X1, Ps1),
    E = env(_, _, _, _, _, Obs),
    member(X1-V, Obs),
    unify_value(P, V, Ps1, Ps).
beval(G:TE, E, Ps0, Ps) :- !,                     % a derived atom at a time
    read_time(TE, E, T),
    split(G, Ps0, G1, Ps1),
    derived(G1, T, E, Ps1, Ps).
beval(V is Ex, E, Ps0, Ps) :- !,
    (   has_col(Ex), var(V)
    ->  E = env(_, N, _, _, _, _),
        plan(Ex, Tmpl, Bs),
        functor(C, c, N),
        arith_loop(Ps0, Bs, Tmpl, C),
        col_ref(C, _, V),
        Ps = Ps0
    ;   ( has_col(V) ; has_col(Ex) )
    ->  test_loop(V =:= Ex, Ps0, Ps)
    ;   V is Ex, Ps = Ps0
    ).
beval(G, E, Ps0, Ps) :-
    (   has_col(G)
    ->  (   test_goal(G)
        ->  test_loop(G, Ps0, Ps)
        ;   split(G, Ps0, G1, Ps1),
            call_static(G1, E),
            Ps = Ps1
        )
    ;   call_static(G, E),
        Ps = Ps0
    ).

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
    test_each(Ps0, Bs, Tmpl, Ps),
    Ps \== [].

test_each([], _, _, []).
test_each([I|Is], Bs, G, Ps) :-
    (   \+ \+ ( bind(Bs, I), call(G) ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    test_each(Is, Bs, G, Ps1).

%   call_static(+G, +Env): a static predicate of the program, a fact of
%   the step, or a builtin.
call_static(G, env(M, _, _, _, Facts, _)) :-
    (   M:'$b_static_pred'(G, Kind)
    ->  (   Kind == derived -> M:'$b_static'(G, B), M:B ; M:G )
    ;   predicate_property(M:G, visible)
    ->  M:G
    ;   member(G, Facts)
    ).

%   split(+T, +Ps0, -T1, -Ps): T with its column references replaced by
%   the particles' values, for each group of particles that share them.
%   (Only the columns' values are grouped: T's own unbound variables stay
%   T1's, for the goals after it.)
split(T, Ps0, T1, Ps) :-
    (   has_col(T)
    ->  plan(T, Tmpl, Bs),
        pairs_keys_values(Bs, Cs, Pats),
        split_pairs(Ps0, Cs, Pairs),
        keysort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups),
        member(Pats-Ps, Groups),
        T1 = Tmpl
    ;   T1 = T, Ps = Ps0
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
    E = env(_, N, _, _, _, _),
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

with_arity([], _, _, []).
with_arity([I|Is], C, K, Ps) :-
    arg(I, C, V),
    (   tuple_arity(V, K) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    with_arity(Is, C, K, Ps1).

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

tuple_arity(V, K) :- K =:= 1, !, V \== '$undef', V \== '$u'.
tuple_arity(V, K) :- nonvar(V), V = (_, B), K1 is K-1, tuple_arity(B, K1).

                 /*******************************
                 *        RANDOM VARIABLES      *
                 *******************************/

%   read_key(+X, +T, +E, +Ps0, -Key, -Entry, -Ps): X's entry at T,
%   computed for the particles of Ps0 that lack it; a non-ground X reads
%   the keys held (the values already drawn), one branch per key.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    ground(X), !,
    value(E, X, T, Ps0, Entry),
    Ps = Ps0.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    env_time_table(E, T, Tab),
    findall(X, tab_match(Tab, X, _), Xs0), sort(Xs0, Xs),
    member(X, Xs),
    tab_get(Tab, X, Entry),
    arg(1, Entry, C),
    defined_at(Ps0, C, Ps),
    Ps \== [].

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
        (   K > 1, \+ ( arg(_, C, V), \+ tuple_arity(V, K) ) -> A = K ; A = none ),
        nb_setarg(3, Entry, A),
        Arity = A
    ).

value_arity(V, K0, K) :-
    (   nonvar(V), V = (_, B) -> K1 is K0+1, value_arity(B, K1, K) ; K = K0 ).

%   value(+E, +X, +T, +Ps, -Entry): X's entry at T with a value (or
%   '$undef') for every particle of Ps.
value(E, X, T, Ps, Entry) :-
    env_time_table(E, T, Tab),
    (   tab_get(Tab, X, Entry0)
    ->  true
    ;   E = env(_, N, _, _, _, _),
        new_column(N, '$u', C0),
        tab_put(Tab, X, e(C0, open, unknown)),
        tab_get(Tab, X, Entry0)
    ),
    Entry = Entry0,
    (   arg(2, Entry, open), E = env(_, _, _, t(_, _, T, _), _, _)
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
    E = env(M, _, _, _, _, _),
    (   T =:= 0 -> K = zero ; K = next ),
    Now is T-1,
    env_now(E, Now, EK),
    env_now(E, T, ES),
    forall(rv_clause(M, X, K, D, B, L),
           assign_clause(EK, B, D, L, Ps, C)),
    forall(rv_clause(M, X, now, D, B, L),
           assign_clause(ES, B, D, L, Ps, C)),
    set_each(Ps, C, '$undef').

rv_clause(M, X, K, D, B, L) :-
    M:'$b_rv'(H, K, D0, B0, L),
    copy_term(H-D0-B0, X1-D-B),
    X1 = X.

%   A distribution error names the clause (file:line), as in ddc.pl.
assign_clause(E, B, D, L, Ps, C) :-
    uncomputed(Ps, C, Rest),
    (   Rest == [] -> true
    ;   catch(forall(beval(B, E, Rest, Ps1), assign(Ps1, C, D)),
              error(ddc_distribution(D1, Why), _),
              ( E = env(M, _, _, _, _, _),
                throw(error(ddc(distribution(D1, Why), M:L), _)) ))
    ).

assign(Ps, C, D) :-
    (   D = val(V), \+ has_col(V)
    ->  set_each(Ps, C, V)
    ;   D = val(V)
    ->  plan(V, Tmpl, Bs),
        instance_each(Ps, Bs, Tmpl, C)
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

draw_each([], _, _, _).
draw_each([I|Is], Bs, P, C) :-
    (   arg(I, C, U), U == '$u'
    ->  \+ \+ ( bind(Bs, I), dist_sample_prepared(P, S), nb_setarg(I, C, S) )
    ;   true
    ),
    draw_each(Is, Bs, P, C).

%   derived(+G, +T, +E, +Ps0, -Ps): G at time T by its clauses (each
%   solution a branch).
derived(G, T, E, Ps0, Ps) :-
    E = env(M, _, _, _, _, _),
    (   T =:= 0 -> K = zero, Now = 0 ; K = next, Now is T-1 ),
    (   M:'$b_der'(H, K, B0, _), Now1 = Now
    ;   M:'$b_der'(H, now, B0, _), Now1 = T
    ),
    copy_term(H-B0, G1-B),
    G1 = G,
    env_now(E, Now1, E1),
    beval(B, E1, Ps0, Ps).

                 /*******************************
                 *            FILTER            *
                 *******************************/

%!  batch_new(+Module, +Items, +File, +N, +Seed, -State) is det.
%
%   N particles at time 0 of the program Items (ddc.pl's classified
%   clauses, already loaded into Module): every h:0 clause's ground heads
%   drawn.  Throws batch_check_program/2's error outside the fragment.
batch_new(M, Items, File, N, Seed, State) :-
    batch_check_program(Items, File),
    compile(M, Items),
    random_property(state(Saved)),
    call_cleanup(
        ( set_random(seed(Seed)),
          tab_new(Tab0), tab_new(Tab),
          E = env(M, N, -1, t(-1, Tab0, 0, Tab), [], []),
          numlist(1, N, All),
          forall(sweep_key(M, zero, E, X), value(E, X, 0, All, _)),
          random_property(state(R)) ),
        set_random(state(Saved))),
    State = bs(M, N, 0, t(-1, Tab0, 0, Tab), [], R).

%   sweep_key(+M, +Kind, +E, -X): a ground head of a Kind clause, from the
%   static goals its body starts with.
sweep_key(M, K, E, X) :-
    findall(X0, ( M:'$b_rv'(H, K, _, B, _), H \= observation(_),
                  copy_term(H-B, X0-B1),
                  static_prefix(B1, M, P),
                  prefix_solutions(P, E),
                  ground(X0) ), Xs0),
    sort(Xs0, Xs),
    member(X, Xs).

static_prefix((A, B), M, P) :- !,
    (   static_goal(A, M) -> P = (A, P1), static_prefix(B, M, P1) ; P = true ).
static_prefix(A, M, P) :-
    (   static_goal(A, M) -> P = A ; P = true ).

static_goal(G, M) :-
    callable(G), G \= _:_, G \= (_ ~= _), G \= (_, _), G \= (_ ; _), G \= (_ -> _),
    G \= (\+ _), G \= findall(_, _, _), G \= findall_forward(_, _, _),
    (   M:'$b_static_pred'(G, _) -> true
    ;   \+ predicate_property(M:G, visible)          % a fact of the step
    ).

prefix_solutions(true, _) :- !.
prefix_solutions((A, B), E) :- !, call_static(A, E), prefix_solutions(B, E).
prefix_solutions(A, E) :- call_static(A, E).

%!  batch_step(+State0, +Observations, +Facts, -Result) is det.
%
%   Result = step(State, LogWeights): every particle advanced from t to
%   t+1 with the Facts (actions and plain observations) of t+1 and
%   weighted by the Observations (terms H ~= V).  State0 is not changed.
batch_step(State0, Obs, Facts, step(State, LWs)) :-
    State0 = bs(M, N, T, t(_, _, _, Tab), _, R0),
    T1 is T+1,
    tab_new(Tab1),
    findall(H-V, member(H ~= V, Obs), HVs),
    E = env(M, N, T, t(T, Tab, T1, Tab1), Facts, HVs),
    numlist(1, N, All),
    random_property(state(Saved)),
    call_cleanup(
        ( set_random(state(R0)),
          new_column(N, 0.0, LW),
          forall(member(H-V, HVs), weigh_observation(E, H, V, All, LW)),
          forall(sweep_key(M, next, E, X), value(E, X, T1, All, _)),
          random_property(state(R)) ),
        set_random(state(Saved))),
    LW =.. [_|LWs],
    duplicate_term(Facts, Facts1),
    State = bs(M, N, T1, t(T, Tab, T1, Tab1), Facts1, R).

%   weigh_observation(+E, +H, +V, +Ps, +LW): the log density of V under
%   H's first applicable clause at t+1, added to each particle's LW.
weigh_observation(E, H, V, Ps, LW) :-
    E = env(M, N, T, _, _, _),
    T1 is T+1,
    new_column(N, '$u', Done),
    forall(rv_clause(M, H, next, D, B, _), weigh_clause(E, B, D, V, Ps, Done, LW)),
    env_now(E, T1, ES),
    forall(rv_clause(M, H, now, D, B, _), weigh_clause(ES, B, D, V, Ps, Done, LW)),
    (   member(I, Ps), arg(I, Done, U), U == '$u'
    ->  throw(error(ddc(no_observation_clause(H ~= V), query), _))
    ;   true
    ).

weigh_clause(E, B, D, V, Ps, Done, LW) :-
    uncomputed(Ps, Done, Rest),
    (   Rest == [] -> true
    ;   forall(beval(B, E, Rest, Ps1),
               ( plan(D, Tmpl, Bs), dist_prepare(Tmpl, P), weigh_each(Ps1, Bs, P, V, Done, LW) ))
    ).

weigh_each([], _, _, _, _, _).
weigh_each([I|Is], Bs, P, V, Done, LW) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), dist_log_density_prepared(P, V, LP), add_log(I, LW, LP) )
    ;   true
    ),
    weigh_each(Is, Bs, P, V, Done, LW).

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
%   Indices[i] (0-based) in both times held.
%   (The new state is made after its tables: a filter keeps it linked, not
%   copied, so it must hold no binding made after it.)
batch_resample(S0, Is0, S) :-
    S0 = bs(M, N, T, t(T0, Tab0, T1, Tab1), Fs, R),
    length(Is0, N),
    maplist(succ, Is0, Is),
    resample_table(Tab0, Is, New0),
    resample_table(Tab1, Is, New1),
    S = bs(M, N, T, t(T0, New0, T1, New1), Fs, R).

resample_table(Tab, Is, New) :-
    tab_new(New),
    forall(tab_match(Tab, K, e(C, S, A)),
           (   S = same(_)
           ->  tab_put(New, K, e(C, S, A))
           ;   args_of(Is, C, Vs),
               C1 =.. [c|Vs],
               ( S == defined -> S1 = defined ; S1 = open ),
               tab_put(New, K, e(C1, S1, A)),
               ( S1 == open -> tab_get(New, K, E1), settle(E1) ; true )
           )).

args_of([], _, []).
args_of([I|Is], C, [V|Vs]) :- arg(I, C, V), args_of(Is, C, Vs).

%!  batch_time(+State, -T) is det.
batch_time(bs(_, _, T, _, _, _), T).

%!  batch_size(+State, -N) is det.
batch_size(bs(_, N, _, _, _, _), N).

%!  batch_holds(+State, +Goal, -Flags) is det.
%
%   Flags: for each particle 1 if Goal holds at the current time (t is the
%   current time), else 0.  Values the goal needs and a particle lacks are
%   drawn and kept (the state's columns are updated in place).
batch_holds(S, Goal, Flags) :-
    query_env(S, E, All, R0),
    with_state(R0, branch_union(Goal, E, All, Ps)),
    S = bs(_, N, _, _, _, _),
    flags(1, N, Ps, Flags).

flags(I, N, _, []) :- I > N, !.
flags(I, N, [I|Ps], [1|Fs]) :- !, I1 is I+1, flags(I1, N, Ps, Fs).
flags(I, N, Ps, [0|Fs]) :- I1 is I+1, flags(I1, N, Ps, Fs).

%!  batch_values(+State, +Template, +Goal, -Values) is det.
%
%   Values: for each particle Template at Goal's first solution of its own,
%   or the atom none.
batch_values(S, Template, Goal, Values) :-
    query_env(S, E, All, R0),
    S = bs(_, N, _, _, _, _),
    new_column(N, none, VC),
    new_column(N, '$u', Done),
    with_state(R0, forall(beval(Goal, E, All, Ps),
                          ( plan(Template, Tmpl, Bs), value_each(Ps, Bs, Tmpl, Done, VC) ))),
    VC =.. [_|Values].

value_each([], _, _, _, _).
value_each([I|Is], Bs, Tmpl, Done, VC) :-
    (   arg(I, Done, U), U == '$u'
    ->  nb_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), nb_setarg(I, VC, Tmpl) )
    ;   true
    ),
    value_each(Is, Bs, Tmpl, Done, VC).

query_env(bs(M, N, T, Tabs, Fs, R), env(M, N, T, Tabs, Fs, []), All, R) :-
    numlist(1, N, All).

%   Queries draw from the state's generator without advancing it for the
%   next step (a query does not change the particles a step will draw).
with_state(R, Goal) :-
    random_property(state(Saved)),
    call_cleanup(( set_random(state(R)), Goal ), set_random(state(Saved))).
