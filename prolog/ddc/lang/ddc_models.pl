/*  ddc_models.pl -- the statistical models and aggregates of learned clauses.

    The goals a learned distributional clause calls in its body to turn the
    values it reads into the parameters of its head's distribution
    (logistic/3, softmax/3, linear/3), and the aggregates it computes over a
    variable's relational neighbours (mean_list/2, mode_list/2,
    antimode_list/2; count, max and min are length/2, max_list/2 and
    min_list/2 of library(lists)).  Re-exported by ddc.pl, so every DC
    program may call them.
*/

:- module(ddc_models,
          [ logistic/3,                 % +Inputs, +Weights, -P
            linear/3,                   % +Inputs, +Weights, -Y
            softmax/3,                  % +Inputs, +WeightRows, -Ps
            mean_list/2,                % +Numbers, -Mean
            mode_list/2,                % +Values, ?Mode
            antimode_list/2             % +Values, ?Value
          ]).

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).

:- set_prolog_flag(optimise, true).

/** <module> Statistical models and aggregates of learned clauses

Weights follow one convention everywhere: one weight per input and the
bias last, [w1, ..., wn, b], for the linear predictor z = w1*x1 + ... +
wn*xn + b.  The paper's learned occluder clause

    occluder(A, O):t+1 ~ finite([P1:true, P2:false]) :=
        ..., distance(A, O):t ~= D, logistic([D], [-16.9, 0.8], P1), P2 is 1 - P1.

gives P1 = 1/(1 + exp(16.9*D - 0.8)): the probability falls with the
distance.
*/

%!  logistic(+Inputs:list(number), +Weights:list(number), -P:float) is det.
%
%   P = 1/(1+exp(-(w1*x1 + ... + wn*xn + b))) with Weights = [w1,...,wn,b].
%   Inputs and weights may be numbers or arithmetic expressions.
%
%   @error domain_error(weights_one_more_than_inputs(N), Weights)
logistic(Inputs, Weights, P) :-
    linear(Inputs, Weights, Z),
    sigmoid(Z, P).

%   sigmoid(+Z, -P): 1/(1+exp(-Z)) without overflow for large |Z|.
sigmoid(Z, P) :-
    (   Z >= 0 -> P is 1/(1+exp(-Z)) ; E is exp(Z), P is E/(1+E) ).

%!  linear(+Inputs:list(number), +Weights:list(number), -Y:float) is det.
%
%   Linear model for Gaussian means: Y = w1*x1 + ... + wn*xn + b with
%   Weights = [w1,...,wn,b].  E.g. `x ~ gaussian(M, 0.1) := y ~= Y,
%   linear([Y], [2.0, 0.5], M).`
%
%   @error domain_error(weights_one_more_than_inputs(N), Weights)
linear(Inputs, Weights, Y) :-
    must_be(list, Inputs),
    must_be(list, Weights),
    length(Inputs, N),
    N1 is N+1,
    (   length(Weights, N1) -> true
    ;   domain_error(weights_one_more_than_inputs(N), Weights)
    ),
    dot(Inputs, Weights, 0.0, Y).

dot([], [B], S, Y) :- Y is S + B.
dot([X|Xs], [W|Ws], S0, Y) :- S is S0 + W*X, dot(Xs, Ws, S, Y).

%!  softmax(+Inputs:list(number), +WeightRows:list(list(number)), -Ps:list(float)) is det.
%
%   Multinomial logistic regression: one row of weights [w1,...,wn,b] per
%   class, P_k = exp(z_k) / sum_j exp(z_j) with z_k the linear predictor of
%   row k.  Learned clauses fix the first row at zeros (the reference class):
%   `colour(A) ~ finite([P1:red, P2:green, P3:blue]) := size(A) ~= S,
%   softmax([S], [[0,0], [1.5,-0.2], [-0.7,0.4]], [P1, P2, P3]).`
%
%   @error domain_error(weights_one_more_than_inputs(N), Row)
%   @error domain_error(non_empty_list, [])
softmax(Inputs, Rows, Ps) :-
    must_be(list, Rows),
    (   Rows == [] -> domain_error(non_empty_list, Rows) ; true ),
    maplist(linear(Inputs), Rows, Zs),
    max_list(Zs, Max),
    foldl(exp_sum(Max), Zs, 0.0, Sum),
    maplist(normalised_exp(Max, Sum), Zs, Ps).

exp_sum(Max, Z, S0, S) :- S is S0 + exp(Z - Max).
normalised_exp(Max, Sum, Z, P) :- P is exp(Z - Max) / Sum.

%!  mean_list(+Numbers:list(number), -Mean:float) is semidet.
%
%   The arithmetic mean; fails on the empty list (an aggregate over no
%   neighbours is undefined).
mean_list(List, Mean) :-
    List = [_|_],
    sum_list(List, Sum),
    length(List, N),
    Mean is Sum / N.

%!  mode_list(+Values:list, ?Mode) is semidet.
%
%   The most frequent value of List; among equally frequent values the
%   first in the standard order of terms.  Fails on the empty list.
mode_list(List, Mode) :-
    value_counts(List, Counts),
    aggregate_extreme(Counts, >, Mode0),
    Mode = Mode0.

%!  antimode_list(+Values:list, ?Value) is semidet.
%
%   The least frequent value of List (DreaML's minMod); among equally
%   frequent values the first in the standard order of terms.  Fails on
%   the empty list.
antimode_list(List, Value) :-
    value_counts(List, Counts),
    aggregate_extreme(Counts, <, Value0),
    Value = Value0.

%   value_counts(+List, -Pairs): Value-Count in the standard order of Value.
value_counts(List, Counts) :-
    List = [_|_],
    msort(List, Sorted),
    clumped(Sorted, Counts).

%   aggregate_extreme(+Counts, +Order, -Value): the first Value whose count
%   is strictly better (Order) than every earlier one.
aggregate_extreme([V-C|Rest], Order, Value) :-
    foldl(better(Order), Rest, V-C, Value-_).

better(Order, V-C, V0-C0, Best) :-
    (   compare(Order, C, C0) -> Best = V-C ; Best = V0-C0 ).
