/*  filter_batched_prototype.pl -- a measurement prototype of docs/batched-filter.md:
    a filter step evaluated clause by clause over columns of particles.

    NOT the engine.  It interprets the fragment of DDC that the benchmark's
    occlusion model (bench/filter_numpy_reference.py) uses, to measure what
    evaluating clauses over all particles at once costs before the engine is
    rebuilt that way:

        .venv/bin/swipl -O bench/filter_batched_prototype.pl -- PROGRAM FRAMES N
        (bench/filter_step.py --batched runs it on the bench's program and frames)

    PROGRAM: a DDC file; FRAMES: terms frame(Observations).  Prints a JSON line
    {"batched_ms_per_step": x, "log_likelihood": y, "resamplings": r}.

    Particles are columns: a random variable's values at a time are one term
    c(V1, ..., VN) ('$u': not computed yet, '$undef': no clause applies).  A
    clause body is evaluated for a batch (a list of particle indices) with its
    variables bound to a value or to a column reference '$c'(C); a goal that
    needs a particle's value as a term (a key argument, a static call) splits
    the batch by value; arithmetic, comparisons and distributions run in one
    loop over the batch through a template made once per goal (plan/3).  A
    random variable's value for a batch: its clauses in order, each over the
    particles no earlier one applied to, computed on first read (lazily, as
    the engine).  A column whose values all agree is read as one value.

    Fragment and limits (an engine would need all of these): static facts
    `p(..) := true` and the step's facts (plain observations such as
    observed/1; a predicate given in no step so far is not known as one);
    random variables h:0 and h:t+1 (val, gaussian, uniform, any distribution
    of ddc_dist); derived h:t+1 atoms; bodies of conjunctions of static calls, \+, reads h:t ~= P and
    h:t+1 ~= P, is/2, comparisons, ==, \==, findall_forward/3 and derived
    calls.  No if-then-else, no h:t clauses, no error messages with clause
    positions, no overlap checks, no threads, no shared store; systematic
    resampling when the ESS falls below 0.9 N (as bridge.Filter).  The random
    draws come in another order than the engine's, so the particles differ;
    the log-likelihood agrees within Monte Carlo error (tests/test_bench_calls.py).
*/
:- use_module('../prolog/ddc_belief').   % (re-exports ../prolog/ddc)
:- use_module('../prolog/ddc_dist').
:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- initialization(main, main).

:- dynamic rv/4, der/3, static/1, sfact/1, step_fact/1, step_pred/1.
%   rv(Head, Time, Dist, Body)   Time: 0 or next
%   der(Head, Time, Body)

load(File) :-
    retractall(rv(_,_,_,_)), retractall(der(_,_,_)), retractall(static(_)), retractall(sfact(_)),
    retractall(step_pred(_)),
    setup_call_cleanup(open(File, read, S),
                       read_all(S),
                       close(S)).

read_all(S) :-
    read_term(S, T, [module(ddc)]),
    (   T == end_of_file -> true
    ;   item(T), read_all(S)
    ).

item((H ~ D := B)) :- !, head_time(H, X, T), assertz(rv(X, T, D, B)).
item((H := true)) :- H \= _:_, !, assertz(sfact(H)), functor(H, N, A), functor(G, N, A),
    ( static(G) -> true ; assertz(static(G)) ).
item((H := B)) :- head_time(H, X, T), assertz(der(X, T, B)).

head_time(X:0, X, 0) :- !.
head_time(X:t+1, X, next) :- !.
head_time(X:t, X, now).

static_goal(G) :- callable(G), G \= _:_, \+ G = (_ ~= _), ( static(G) -> true ; step_pred(G) ).

%   ---------------------------------------------------------------- columns
%   Cols: a table Key-Time -> c(V1..VN); '$u' not computed.  A fixed number
%   of buckets, each a chain to which an entry is linked (copied once, when
%   put; never again), so that a column taken from the table stays the
%   table's own while other keys are added (nb_setarg/3 on it lasts).
ct_new(T) :- functor(T, ct, 4096).

ct_get(T, K, V) :-
    term_hash(K, H), I is H mod 4096 + 1,
    arg(I, T, L), nonvar(L), memberchk(K-V0, L), V = V0.

ct_put(T, K, V) :-
    term_hash(K, H), I is H mod 4096 + 1,
    arg(I, T, L),
    duplicate_term(K-V, E),
    (   var(L) -> nb_linkarg(I, T, [E]) ; nb_linkarg(I, T, [E|L]) ).

ct_match(T, K, V) :-
    arg(_, T, L), nonvar(L), member(K-V, L).

ct_filter(T, Keep, T1) :-
    ct_new(T1),
    forall(( ct_match(T, K, V), call(Keep, K, V) ), ct_put(T1, K, V)).

col(Cols, N, K, C) :-
    (   ct_get(Cols, K, C) -> true
    ;   functor(C0, c, N), fill(N, C0, '$u'), ct_put(Cols, K, C0), ct_get(Cols, K, C)
    ).

fill(0, _, _) :- !.
fill(I, C, V) :- arg(I, C, V), I1 is I-1, fill(I1, C, V).

%   ---------------------------------------------------------------- evaluation
%   env(Cols, N, T1): T1 the time being computed (t+1).
time_of(now, env(_, _, T1), T) :- T is T1-1.
time_of(next, env(_, _, T1), T1).
time_of(0, _, 0).

read_time(t, E, T) :- !, time_of(now, E, T).
read_time(t+1, E, T) :- !, time_of(next, E, T).

%   value(+E, +Key, +Time, +Ps, -C): the column of Key at Time, computed
%   for the particles of Ps that lack it.
value(E, X, T, Ps, C) :-
    E = env(Cols, N, _),
    col(Cols, N, X-T, C),
    (   ct_get(Cols, '$complete'(X-T), _)
    ->  true
    ;   include(uncomputed(C), Ps, Miss),
        (   Miss == [] -> true
        ;   compute(E, X, T, Miss, C)
        ),
        (   \+ ( arg(_, C, V), V == '$u' )
        ->  (   arg(1, C, V1), \+ ( arg(_, C, V), V \== V1 ) -> U = same(V1)
            ;   arg(_, C, '$undef') -> U = undef
            ;   U = defined
            ),
            ct_put(Cols, '$complete'(X-T), U)
        ;   true
        )
    ).

uncomputed(C, I) :- arg(I, C, V), V == '$u'.

compute(E, X, T, Ps, C) :-
    ( T == 0 -> K = 0 ; E = env(_, _, T1), T == T1 -> K = next ; K = none ),
    forall(( clause_copy(X, K, D, B) ),
           ( include(uncomputed(C), Ps, Rest),
             (   Rest == [] -> true
             ;   forall(beval(B, E, Rest, Ps1), assign(Ps1, C, D))
             ) )),
    forall(( member(I, Ps), arg(I, C, V), V == '$u' ), nb_setarg(I, C, '$undef')).

clause_copy(X, K, D, B) :-
    rv(H, K, D0, B0),
    copy_term(H-D0-B0, X1-D-B),
    X1 = X.

assign(Ps, C, D) :-
    plan(D, Tmpl, Bs),
    forall(( member(I, Ps), arg(I, C, V), V == '$u' ),
           ( bind(Bs, I), dist_sample(Tmpl, S), nb_setarg(I, C, S) )).

%   plan(+T, -Tmpl, -Binds): Tmpl is T with each column reference
%   '$c'(C) replaced by a fresh variable V, Binds the C-V pairs: one walk
%   per batch; per particle only bind/2 (arg/3), under forall/2 so that
%   the bindings are undone.
plan(T, T, []) :- var(T), !.
plan('$c'(C), V, [C-V]) :- !.
plan(T, T, []) :- atomic(T), !.
plan(T, T1, Bs) :-
    compound_name_arguments(T, F, As),
    plan_args(As, As1, Bs),
    compound_name_arguments(T1, F, As1).
plan_args([], [], []).
plan_args([A|As], [A1|As1], Bs) :-
    plan(A, A1, B1), plan_args(As, As1, B2), append(B1, B2, Bs).

bind([], _).
bind([C-V|Bs], I) :- arg(I, C, V), bind(Bs, I).

has_col(T) :- compound(T), ( T = '$c'(_) -> true ; arg(_, T, A), has_col(A) ), !.

%   beval(+Body, +E, +Ps0, -Ps): nondeterministic over branches (solutions
%   of static goals, splits by value); Ps the particles of the branch.
beval(_, _, [], _) :- !, fail.
beval(true, _, Ps, Ps) :- !.
beval((A, B), E, Ps0, Ps) :- !,
    beval(A, E, Ps0, Ps1),
    beval(B, E, Ps1, Ps).
beval(\+ G, E, Ps0, Ps) :- !,
    (   \+ has_col(G), static_goal(G)
    ->  \+ call_static(G), Ps = Ps0
    ;   findall(Ps1, beval(G, E, Ps0, Ps1), Ls), append(Ls, Done0), sort(Done0, Done),
        ord_subtract(Ps0, Done, Ps), Ps \== []
    ).
beval(findall_forward(T, G, L), E, Ps0, Ps) :- !,
    E = env(_, N, _),
    functor(LC, c, N),
    forall(member(I, Ps0), nb_setarg(I, LC, [])),
    forall(beval(G, E, Ps0, Ps1),
           ( plan(T, Tmpl, Bs),
             forall(member(I, Ps1), ( bind(Bs, I), arg(I, LC, L0), append(L0, [Tmpl], L1), nb_setarg(I, LC, L1) )) )),
    unify_col(L, LC, Ps0, Ps).
beval(X:TE ~= P, E, Ps0, Ps) :- !,
    split(X, Ps0, X1, Ps1),
    read_time(TE, E, T),
    value(E, X1, T, Ps1, C),
    unify_read(P, E, X1-T, C, Ps1, Ps).
beval(V is Ex, _, Ps0, Ps) :- !,
    (   has_col(Ex)
    ->  arith_col(Ex, Ps0, C),
        unify_col(V, C, Ps0, Ps)
    ;   V is Ex, Ps = Ps0
    ).
beval(G, _, Ps0, Ps) :-
    compound(G), functor(G, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=, ==, \==]), !,
    (   has_col(G)
    ->  plan(G, Tmpl, Bs),
        findall(I, ( member(I, Ps0), \+ \+ ( bind(Bs, I), call(Tmpl) ) ), Ps), Ps \== []
    ;   call(G), Ps = Ps0
    ).
beval(G:TE, E, Ps0, Ps) :- !,                    % derived timed atom
    read_time(TE, E, T),
    E = env(_, _, T1),
    ( T == T1 -> K = next ; K = now ),
    split(G, Ps0, G1, Ps1),
    der(H, K, B0),
    copy_term(H-B0, H1-B),
    H1 = G1,
    beval(B, E, Ps1, Ps).
beval(G, _, Ps0, Ps) :-                          % static
    split(G, Ps0, G1, Ps),
    call_static(G1).

call_static(G) :- ( sfact(G) ; step_fact(G) ).

%   split(+T, +Ps0, -T1, -Ps): T with its column references replaced by
%   values, for each group of particles that share them.
split(T, Ps0, T1, Ps) :-
    (   has_col(T)
    ->  plan(T, Tmpl, Bs),
        findall(Tmpl-I, ( member(I, Ps0), bind(Bs, I) ), Pairs),
        keysort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups),
        member(T1-Ps, Groups)
    ;   T1 = T, Ps = Ps0
    ).

%   unify_read(?P, +E, +Key, +C, +Ps0, -Ps): as unify_col/4, and for a
%   complete column: one value if all agree; else, without undefined values,
%   no filtering, and a tuple's projections made once per column.
unify_read(P, env(Cols, N, _), K, C, Ps0, Ps) :-
    (   ct_get(Cols, '$complete'(K), same(V))
    ->  V \== '$undef',
        (   P = V -> true ; number(V), number(P), V =:= P ),
        Ps = Ps0
    ;   ct_get(Cols, '$complete'(K), defined)
    ->  Ps = Ps0,
        (   var(P)
        ->  P = '$c'(C)
        ;   P = (A, _), var(A)
        ->  (   ct_get(Cols, '$proj'(K), Cs) -> true
            ;   numlist(1, N, All), tuple_vars(P, Vs0), length(Vs0, L), length(Cs0, L),
                maplist(new_col(N), Cs0),
                forall(member(I, All), ( arg(I, C, V), tuple_vals(V, Xs), set_all(Cs0, I, Xs) )),
                ct_put(Cols, '$proj'(K), Cs0), ct_get(Cols, '$proj'(K), Cs)
            ),
            tuple_vars(P, Vs),
            maplist(col_ref, Vs, Cs)
        ;   unify_col(P, C, Ps0, Ps)
        )
    ;   unify_col(P, C, Ps0, Ps)
    ).

%   unify_col(?P, +C, +Ps0, -Ps): pattern P against column C's values, for
%   the particles Ps0 (Ps: those where they unify).
unify_col(P, C, Ps0, Ps) :-
    (   var(P)
    ->  P = '$c'(C), exclude(undef_at(C), Ps0, Ps)
    ;   P = (A, _), var(A)
    ->  project(P, C, Ps0, Ps)
    ;   include(value_is(C, P), Ps0, Ps)
    ),
    Ps \== [].

undef_at(C, I) :- arg(I, C, V), V == '$undef'.
value_is(C, P, I) :- arg(I, C, V), V \== '$undef', ( V = P -> true ; number(V), number(P), V =:= P ).

project(P, C, Ps0, Ps) :-
    exclude(undef_at(C), Ps0, Ps),
    tuple_vars(P, Vs),
    length(Vs, K), arg(1, C, _),
    functor(C, _, N),
    length(Cs, K),
    maplist(new_col(N), Cs),
    forall(member(I, Ps), ( arg(I, C, V), tuple_vals(V, Xs), set_all(Cs, I, Xs) )),
    maplist(col_ref, Vs, Cs).

new_col(N, C) :- functor(C, c, N).
col_ref(V, C) :- V = '$c'(C).

tuple_vars(T, [T]) :- var(T), !.
tuple_vars((A, B), [A|Vs]) :- !, tuple_vars(B, Vs).
tuple_vars(A, [A]).
tuple_vals((A, B), [A|Vs]) :- !, tuple_vals(B, Vs).
tuple_vals(A, [A]).
set_all([], _, []).
set_all([C|Cs], I, [X|Xs]) :- nb_setarg(I, C, X), set_all(Cs, I, Xs).

arith_col(Ex, Ps, C) :-
    once(sub_term('$c'(C0), Ex)),
    functor(C0, c, N),
    functor(C, c, N),
    plan(Ex, Tmpl, Bs),
    forall(member(I, Ps), ( bind(Bs, I), V is Tmpl, nb_setarg(I, C, V) )).

%   ---------------------------------------------------------------- the step
step(Cols, N, T1, Obs, LWs) :-
    retractall(step_fact(_)),
    forall(member(O, Obs), ( O = (_ ~= _) -> true ; assertz(step_fact(O)) )),
    %   a predicate given as a fact of some step is a static goal in every step
    forall(( step_fact(F), functor(F, Na, Ar), functor(P, Na, Ar), \+ step_pred(P) ),
           assertz(step_pred(P))),
    E = env(Cols, N, T1),
    numlist(1, N, All),
    %   observations: density of the first applicable clause
    functor(LW, c, N), fill(N, LW, 0.0),
    forall(member(observation(X) ~= V, Obs),
           (   functor(OC, c, N), fill(N, OC, '$u'),
               forall(( clause_copy(observation(X), next, D, B) ),
                      ( include(uncomputed(OC), All, Rest),
                        (   Rest == [] -> true
                        ;   forall(beval(B, E, Rest, Ps1), weigh(Ps1, OC, D, V, LW))
                        ) ))
           )),
    %   sweep: every candidate key of the transition clauses
    forall(( rv(H, next, _, B), H \= observation(_), candidates(H, B, X) ),
           value(E, X, T1, All, _)),
    LW =.. [_|LWs].

candidates(H, B, X) :-
    copy_term(H-B, X-B1),
    prefix_static(B1, P),
    call_static_conj(P),
    ground(X).

prefix_static((A, B), P) :- !, ( static_goal(A) -> P = (A, P1), prefix_static(B, P1) ; P = true ).
prefix_static(A, P) :- ( static_goal(A) -> P = A ; P = true ).

call_static_conj(true) :- !.
call_static_conj((A, B)) :- !, call_static(A), call_static_conj(B).
call_static_conj(A) :- call_static(A).

weigh(Ps, OC, D, V, LW) :-
    plan(D, Tmpl, Bs),
    forall(( member(I, Ps), arg(I, OC, U), U == '$u' ),
           ( nb_setarg(I, OC, done),
             bind(Bs, I), dist_log_density(Tmpl, V, LP),
             arg(I, LW, L0), L is L0 + LP, nb_setarg(I, LW, L) )).

prior(Cols, N) :-
    E = env(Cols, N, 0),
    numlist(1, N, All),
    forall(( rv(H, 0, _, B), candidates(H, B, X) ), value(E, X, 0, All, _)).

main(Argv) :- Argv \= [_, _, _], !, format(user_error, "usage: swipl -O bench/filter_batched_prototype.pl -- PROGRAM FRAMES N (got ~q)~n", [Argv]), halt(2).
main([Prog, FramesFile, NA]) :-
    atom_number(NA, N),
    load(Prog),
    load_files(FramesFile, [module(user)]),
    findall(O, user:frame(O), Frames),
    set_random(seed(1)),
    ct_new(Cols0),
    prior(Cols0, N),
    L0 is -log(N),
    length(LWs0, N), maplist(=(L0), LWs0),
    statistics(cputime, T0),
    foldl(run_step(N), Frames, s(1, Cols0, LWs0, 0.0, 0), s(_, _, _, LL, R)),
    statistics(cputime, T1),
    length(Frames, K),
    Ms is 1000*(T1-T0)/K,
    format("{\"batched_ms_per_step\": ~4f, \"log_likelihood\": ~6f, \"resamplings\": ~w}~n",
           [Ms, LL, R]).

keep_time(T0, K, _) :- \+ key_time_is(K, T0).
key_time_is(_-T, T) :- !.
key_time_is('$complete'(_-T), T) :- !.
key_time_is('$proj'(_-T), T).

%   One step: the step's log weights are added to the normalised ones, the
%   log-likelihood grows by their log-sum-exp, and the particles are
%   resampled (systematic) when the ESS falls below 0.9 N, as bridge.Filter.
run_step(N, Obs, s(T1, Cols, LWs0, LL0, R0), s(T2, Cols2, LWs, LL, R)) :-
    step(Cols, N, T1, Obs, StepLWs),
    maplist(plus_f, LWs0, StepLWs, Comb),
    max_list(Comb, Max),
    foldl(add_exp(Max), Comb, 0.0, Sum),
    Inc is Max + log(Sum),
    LL is LL0 + Inc,
    maplist(minus_f(Inc), Comb, LWs1),
    foldl(add_sq, LWs1, 0.0, Sq),
    T0 is T1 - 1,
    ct_filter(Cols, keep_time(T0), Cols1),
    (   1/Sq < 0.9*N
    ->  systematic(LWs1, Is),
        ct_new(Cols2),
        forall(( ct_match(Cols1, K, C), K = _-_ ),
               ( resampled(C, Is, C1), ct_put(Cols2, K, C1) )),
        L is -log(N), length(LWs, N), maplist(=(L), LWs),
        R is R0 + 1
    ;   Cols2 = Cols1, LWs = LWs1, R = R0
    ),
    T2 is T1 + 1.

plus_f(A, B, C) :- C is A + B.
minus_f(A, X, Y) :- Y is X - A.
add_exp(M, X, S0, S) :- S is S0 + exp(X - M).
add_sq(X, S0, S) :- S is S0 + exp(2*X).
exp_f(L, W) :- W is exp(L).

%   Systematic resampling as bridge.Filter and ddc_belief (1-based indices).
systematic(LWs, Is) :-
    U is random_float,
    maplist(exp_f, LWs, Ws),
    resample_indices(systematic, Ws, [U], Is0),
    maplist(succ, Is0, Is).

resampled(C, Is, C1) :-
    maplist(arg_of(C), Is, Vs),
    C1 =.. [c|Vs].
arg_of(C, I, V) :- arg(I, C, V).
