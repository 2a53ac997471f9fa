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

:- use_module(ddc_dist).
:- use_module(ddc_batch_columns,
              [plan/3, bind/2, has_column/1, compiled_instance/4]).

:- set_prolog_flag(optimise, true).

/** <module> Draws and densities over a batch

A distribution's parameters may read columns and deferred expressions
(ddc_batch_columns.pl): plan/3 gives its template and the bindings of
each particle.  The distribution is prepared once per batch
(ddc_dist:dist_prepare/2: the Cholesky factor of a covariance the batch
shares); a gaussian whose mean is a column's tuple draws and weighs from
the column's value itself (dist_sample_at/3, dist_log_density_at/4).

Columns are read and written by particle index (arg/3, nb_setarg/3):
they are arrays, not records.
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
    ->  plan(V, Tmpl, Bs),
        (   Ps = [_, _, _, _, _, _, _, _, _, _, _, _, _, _, _, _|_]
        ->  compiled_instance(Ps, Bs, Tmpl, C)
        ;   instance_each(Ps, Bs, Tmpl, C)
        )
    ;   plan(D, Tmpl, Bs),
        dist_prepare(Tmpl, P),
        draw_each(Ps, Bs, P, C)
    ).

%!  set_each(+Ps:list(integer), !Column, +Value) is det.
%
%   Each particle of Ps whose value in Column is not drawn yet gets Value.
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

%   add_log(+I, !LW, +LP): particle I's log weight plus LP (minus infinity
%   stays so, a finite log weight plus minus infinity becomes it).
add_log(I, LW, LP) :-
    arg(I, LW, L0),
    (   L0 > -1.0e308, LP > -1.0e308
    ->  L is L0 + LP, nb_setarg(I, LW, L)
    ;   minus_infinity(L0) -> true
    ;   nb_setarg(I, LW, LP)
    ).

minus_infinity(X) :- float(X), X < -1.0e308.
