%%% -*- Mode: Prolog; -*-
% Examples in the style of the Church tutorial (the original's church-dc.pl),
% with its test predicates: eval_query/7 and eval_query_distribution/8.
%   swipl -g "test_all(10000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/church.pl

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_inference(backward(lw)).
:- initialization(init).

coin ~ finite([0.5:true,0.5:false]).
trickcoin ~ finite([0.95:h,0.05:t]).

fair-coin ~ finite([0.5:true,0.5:false]).
bent-coin ~ finite([0.7:h,0.3:t]) := fair-coin ~= false.
bent-coin ~ finite([0.1:h,0.9:t]) := fair-coin ~= true.

lung-cancer(_) ~ finite([0.01:true,0.99:false]).
cold(_) ~ finite([0.2:true,0.8:false]).
cough(P) := lung-cancer(P) ~= true.
cough(P) := cold(P) ~= true.

breast_cancer ~ finite([0.01:true,0.99:false]).
positive_mammogram ~ finite([0.8:true,0.2:false]) := breast_cancer ~= true.
positive_mammogram ~ finite([0.096:true,0.904:false]) := breast_cancer ~= false.

a ~ finite([0.1:1,0.9:0]).
b ~ finite([0.1:1,0.9:0]).
c ~ finite([0.1:1,0.9:0]).
d ~ val(D) := a ~= A, b ~= B, c ~= C, D is A+B+C.

test_coin(N) :- init, eval_query([],[],coin ~= true,N,P,_,_), writeln(coin(P)).                 % 0.5
test_flip(N) :- init, eval_query([],[],true(0.5),N,P,_,_), writeln(flip(P)).                    % 0.5
test_trick(N) :- init, eval_query([],[],trickcoin ~= h,N,P,_,_), writeln(trickcoin(P)).         % 0.95
test_bent(N) :- init, eval_query([],[],bent-coin ~= h,N,P,_,_), writeln(bent_coin(P)).          % 0.4
test_cough(N) :- init, eval_query([],[],cough(bob),N,P,_,_), writeln(cough(P)).                 % 0.208
test_mammogram(N) :-
	init,
	eval_query([positive_mammogram ~= true],[],breast_cancer ~= true,N,P,_,_),
	writeln(breast_cancer(P)).                                                               % 0.077640
test_conditional(N) :-
	init,
	eval_query_distribution(X,[(d ~= D,D >= 2)],[],a ~= X,N,LP,_,_),
	writeln(a_given_d(LP)).                                 % [0.321429:0, 0.678571:1]
test_all(N) :-
	test_coin(N), test_flip(N), test_trick(N), test_bent(N), test_cough(N),
	test_mammogram(N), test_conditional(N).
