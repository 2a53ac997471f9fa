/*  ddc_batch_rv.pl -- draws and densities of random variables over a batch.

    Part of the batched particle filter (ddc_batch.pl, the API): once a
    clause's body has given a batch of particles (ddc_batch_eval.pl), the
    loops here draw the clause's distribution into the variable's column,
    or add the log density of an observed value to the particles' log
    weights.
*/

:- module(ddc_batch_rv,
          [ assign/3,                   % +Ps, !Column, +Dist
            set_each/3,                 % +Ps, !Column, +Value
            weigh_branch/5              % +Dist, +Value, !Done, !LogWeights, +Ps
          ]).

:- use_module(library(apply)).
:- use_module('../lang/ddc_dist').
:- use_module(ddc_batch_col).
:- use_module(ddc_batch_columns,
              [plan/3, bind/2, has_column/1, compiled_instance/4, vm_finite/4]).

:- set_prolog_flag(optimise, true).

/** <module> Draws and densities over a batch

A distribution's parameters may read columns and deferred expressions
(ddc_batch_columns.pl): plan/3 gives its template and the bindings of
each particle.  The distribution is prepared once per batch
(ddc_dist:dist_prepare/2: the Cholesky factor of a covariance the batch
shares); a gaussian whose mean is a column's tuple draws and weighs from
the column's value itself (dist_sample_at/3, dist_log_density_at/4).

Columns (ddc_batch_col.pl) are read and written by particle index
(col_arg/3, col_setarg/3): they are arrays, not records.  A gaussian
drawn or weighed at a column's values runs in one call of the compiled
column library where it is loaded (col_draw_gauss/5, col_weigh_gauss/7),
its random numbers from a generator seeded from the group's stream.
*/

%!  assign(+Ps:list(integer), !Column, +Dist) is det.
%
%   Each particle of Ps whose value in Column is not drawn yet ('$u') gets
%   a draw of Dist (val(V): V's instance).
%
%   @error ddc(unbound_distribution, _) if Dist is unbound (the caller
%          names the clause).
assign(_, _, D) :-
    var(D), !,
    throw(error(ddc(unbound_distribution, _), _)).      % (clause_error/2 names the clause)
assign(Ps, C, D) :-
    (   D = val(V), \+ has_column(V)
    ->  set_each(Ps, C, V)
    ;   D = val(V)
    ->  (   col_instance(Ps, V, C)
        ->  true
        ;   plan(V, Tmpl, Bs),
            (   ps_size(Ps, K), K >= 16
            ->  compiled_instance(Ps, Bs, Tmpl, C)
            ;   ps_list(Ps, L),
                instance_each(L, Bs, Tmpl, C)
            )
        )
    ;   D = gaussian(Ms, Cov), col_backend(foreign),
        gaussian_in_bulk(Ms, Cov, P),
        mean_source(Ps, Ms, C, Ps1, MC)
    ->  draw_at(Ps1, MC, P, C)
    ;   plan(D, Tmpl, Bs),
        (   Tmpl = uniform(L), Bs = [LC-Pat], var(Pat), L == Pat,
            col_backend(foreign),
            random_between(0, 0x3fffffffffffffff, Seed),
            col_draw_uniform(Ps, LC, C, Seed)
        ->  true
        ;   Tmpl = finite(Es), col_backend(foreign),
            vm_finite(Ps, Bs, Es, C)
        ->  true
        ;   prepared(Tmpl, P),
            draw_each(Ps, Bs, P, C)
        )
    ).

%   gaussian_in_bulk(+Means, +Cov, -P): a gaussian whose mean, a list of
%   three or one, is numbers and expressions over columns (column
%   references, deferred expressions) and whose covariance is ground,
%   drawn and weighed in the column library with P's factor (the
%   distribution prepared from the goal's own terms: no plan/3).
gaussian_in_bulk(Ms, Cov, P) :-
    ground(Cov), \+ has_column(Cov),
    (   is_list(Ms)
    ->  Ms = [M1, M2, M3], bulk_mean(M1), bulk_mean(M2), bulk_mean(M3),
        prepared(gaussian([_, _, _], Cov), P)
    ;   bulk_mean(Ms),
        prepared(gaussian(_, Cov), P)
    ),
    dist_prepared_factor(P, _, _).

bulk_mean(M) :-
    (   number(M) -> true
    ;   compound(M), ( M = '$c'(_, _, _) -> true ; M = '$x'(_) )
    ).

%   mean_source(+Ps, +Means, +C, -Ps1, -MC): the particles Ps1 of Ps to draw
%   or weigh and a column MC of their means: Means read from one column
%   (pos(O):t ~= (X, Y, Z), gaussian([X, Y, Z], ...)) is that column, for
%   all of Ps; else those of Ps not done in C, with their means computed
%   (one value for all, or in the column library: fails where it cannot).
mean_source(Ps, Ms, _, Ps, MC) :-
    one_column_mean(Ms, MC), !.
mean_source(Ps, Ms, C, Ps1, MC) :-
    (   Ms = [M1, M2, M3] -> T = (M1, M2, M3) ; T = Ms ),
    col_size(C, N),
    col_uncomputed(Ps, C, Ps1),
    (   has_column(T)
    ->  col_new(N, '$u', MC),
        col_instance(Ps1, T, MC)
    ;   col_new(N, T, MC)
    ).

one_column_mean(Ms, MC) :-
    (   Ms = [A, B, C]
    ->  A = '$c'(MC, P, X), B = '$c'(MC1, P1, Y), C = '$c'(MC2, P2, Z),
        MC1 == MC, MC2 == MC, P1 == P, P2 == P, P == (X, Y, Z),
        var(X), var(Y), var(Z), X \== Y, Y \== Z, X \== Z
    ;   Ms = '$c'(MC, P, X), var(X), P == X
    ).

%   prepared(+Tmpl, -P): dist_prepare/2 of a distribution template,
%   remembered per template for a gaussian whose mean is variables (bound
%   per particle) and whose covariance is ground: the covariance is
%   usually the program's, the same at every step, and its check and
%   Cholesky factor are worked out once, not once per batch.  (At most
%   max_prepared/1 templates are remembered, in case a program's
%   covariances change from step to step.)
prepared(Tmpl, P) :-
    Tmpl = gaussian(M, V),
    ( var(M) ; is_list(M), maplist(var, M) ),
    ground(V), !,
    variant_sha1(Tmpl, Key),
    (   '$b_prepared'(Key, Tmpl, P0)
    ->  P = P0
    ;   dist_prepare(Tmpl, P),
        flag('$b_prepared', K, K+1),
        (   max_prepared(Max), K < Max -> assertz('$b_prepared'(Key, Tmpl, P)) ; true )
    ).
prepared(Tmpl, P) :-
    dist_prepare(Tmpl, P).

:- dynamic '$b_prepared'/3.

max_prepared(1000).

%!  set_each(+Ps:list(integer), !Column, +Value) is det.
%
%   Each particle of Ps whose value in Column is not drawn yet gets Value.
set_each(Ps, C, V) :-
    col_set_each(Ps, C, V).

instance_each([], _, _, _).
instance_each([I|Is], Bs, Tmpl, C) :-
    (   col_is_u(I, C)
    ->  \+ \+ ( bind(Bs, I), col_setarg(I, C, Tmpl) )
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
draw_each(Ps0, Bs, P, C) :-
    col_backend(foreign),
    col_uncomputed(Ps0, C, Ps),
    mean_column(Ps, Bs, P, C, Means), !,
    draw_at(Ps, Means, P, C).
draw_each(Ps, [C1-Pat], P, C) :- !,
    ps_list(Ps, L),
    draw_each1(L, C1, Pat, P, C).
draw_each(Ps, Bs, P, C) :-
    ps_list(Ps, L),
    draw_loop(L, Bs, P, C).

draw_loop([], _, _, _).
draw_loop([I|Is], Bs, P, C) :-
    (   col_is_u(I, C)
    ->  \+ \+ ( bind(Bs, I), dist_sample_prepared(P, S), col_setarg(I, C, S) )
    ;   true
    ),
    draw_loop(Is, Bs, P, C).

%   draw_at(+Ps, +C1, +P, !C): a draw of P at each particle's mean in C1
%   (in one call of the column library where it can).
draw_at(Ps, C1, P, C) :-
    col_backend(foreign),
    dist_prepared_factor(P, Factor, _),
    random_between(0, 0x3fffffffffffffff, Seed),
    col_draw_gauss(Ps, C1, Factor, C, Seed), !.
draw_at(Ps, C1, P, C) :-
    ps_list(Ps, L),
    draw_at_each(L, C1, P, C).

draw_at_each([], _, _, _).
draw_at_each([I|Is], C1, P, C) :-
    (   col_is_u(I, C)
    ->  col_arg(I, C1, Mean),
        dist_sample_at(P, Mean, S),
        col_setarg(I, C, S)
    ;   true
    ),
    draw_at_each(Is, C1, P, C).

draw_each1([], _, _, _, _).
draw_each1([I|Is], C1, Pat, P, C) :-
    (   col_is_u(I, C)
    ->  \+ \+ ( col_arg(I, C1, Pat), dist_sample_prepared(P, S), col_setarg(I, C, S) )
    ;   true
    ),
    draw_each1(Is, C1, Pat, P, C).

%   mean_column(+Ps, +Binds, +P, +Like, -Means): the prepared gaussian P's
%   mean in each particle of Ps as a column (of Like's size): the same
%   mean everywhere (Binds []) or computed from the binds (in one call of
%   the column library where it can), for draw_at/4 and weigh_at/6.
mean_column(Ps, Bs, P, Like, Means) :-
    dist_mean_slots(P, Slots),
    col_size(Like, N),
    (   Bs == []
    ->  ground(Slots), col_new(N, Slots, Means)
    ;   col_new(N, '$u', Means),
        compiled_instance(Ps, Bs, Slots, Means)
    ).

%!  weigh_branch(+Dist, +Value, !Done, !LogWeights, +Ps:list(integer)) is det.
%
%   Each particle of Ps not weighed yet (Done's '$u') is marked done and
%   its log weight in the column LogWeights gets the log density of Value
%   under Dist.
%
%   @error ddc(unbound_distribution, _) if Dist is unbound.
weigh_branch(D, _, _, _, _) :-
    var(D), !,
    throw(error(ddc(unbound_distribution, _), _)).
weigh_branch(gaussian(Ms, Cov), V, Done, LW, Ps) :-
    col_backend(foreign),
    gaussian_in_bulk(Ms, Cov, P),
    mean_source(Ps, Ms, Done, Ps1, MC),
    dist_prepared_factor(P, Factor, LogNorm),
    col_weigh_gauss(Ps1, MC, Factor, LogNorm, V, Done, LW), !.
weigh_branch(D, V, Done, LW, Ps) :-
    plan(D, Tmpl, Bs),
    prepared(Tmpl, P),
    weigh_each(Ps, Bs, P, V, Done, LW).

weigh_each(Ps, [C1-Pat], P, V, Done, LW) :-
    dist_mean_slots(P, Slots), Slots == Pat, !,
    weigh_at(Ps, C1, P, V, Done, LW).
weigh_each(Ps0, Bs, P, V, Done, LW) :-
    col_backend(foreign),
    col_uncomputed(Ps0, Done, Ps),
    mean_column(Ps, Bs, P, LW, Means), !,
    weigh_at(Ps, Means, P, V, Done, LW).
weigh_each(Ps, [C1-Pat], P, V, Done, LW) :- !,
    ps_list(Ps, L),
    weigh_each1(L, C1, Pat, P, V, Done, LW).
weigh_each(Ps, Bs, P, V, Done, LW) :-
    ps_list(Ps, L),
    weigh_loop(L, Bs, P, V, Done, LW).

weigh_loop([], _, _, _, _, _).
weigh_loop([I|Is], Bs, P, V, Done, LW) :-
    (   col_is_u(I, Done)
    ->  col_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), dist_log_density_prepared(P, V, LP), add_log(I, LW, LP) )
    ;   true
    ),
    weigh_loop(Is, Bs, P, V, Done, LW).

%   weigh_at(+Ps, +C1, +P, +V, !Done, !LW): the log density of V under P
%   at each particle's mean in C1 (in one call of the column library where
%   it can).
weigh_at(Ps, C1, P, V, Done, LW) :-
    col_backend(foreign),
    dist_prepared_factor(P, Factor, LogNorm),
    col_weigh_gauss(Ps, C1, Factor, LogNorm, V, Done, LW), !.
weigh_at(Ps, C1, P, V, Done, LW) :-
    ps_list(Ps, L),
    weigh_at_each(L, C1, P, V, Done, LW).

weigh_at_each([], _, _, _, _, _).
weigh_at_each([I|Is], C1, P, V, Done, LW) :-
    (   col_is_u(I, Done)
    ->  col_setarg(I, Done, done),
        col_arg(I, C1, Mean),
        dist_log_density_at(P, Mean, V, LP),
        add_log(I, LW, LP)
    ;   true
    ),
    weigh_at_each(Is, C1, P, V, Done, LW).

weigh_each1([], _, _, _, _, _, _).
weigh_each1([I|Is], C1, Pat, P, V, Done, LW) :-
    (   col_is_u(I, Done)
    ->  col_setarg(I, Done, done),
        \+ \+ ( col_arg(I, C1, Pat), dist_log_density_prepared(P, V, LP), add_log(I, LW, LP) )
    ;   true
    ),
    weigh_each1(Is, C1, Pat, P, V, Done, LW).

%   add_log(+I, !LW, +LP): particle I's log weight plus LP (minus infinity
%   stays so, a finite log weight plus minus infinity becomes it).
add_log(I, LW, LP) :-
    col_arg(I, LW, L0),
    (   L0 > -1.0e308, LP > -1.0e308
    ->  L is L0 + LP, col_setarg(I, LW, L)
    ;   minus_infinity(L0) -> true
    ;   col_setarg(I, LW, LP)
    ).

minus_infinity(X) :- float(X), X < -1.0e308.
