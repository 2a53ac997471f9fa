%%% -*- Mode: Prolog; -*-
% The original DC system's tutorial, written as its users wrote programs:
% the original header and options, and test predicates that call the
% original's query/5.  Run:
%   swipl -g "test_balls2(10000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/tutorial.pl
%   ddc query prolog/examples/dc/tutorial.pl 'drawn(1) ~= X, color(X) ~= black'

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_inference(backward(lw)).

:- initialization(init).

% a biased coin
coin ~ finite([0.2:true,0.8:false]).

test_coin(N) :-
	init,
	query([],[],coin ~= true,N,P),
	write('probability coin=true: '),writeln(P).    % exact 0.2

color ~ finite([0.1:black,0.5:red,0.4:blue]).

test_color(N) :-
	init,
	query([],[],color ~= black,N,P),
	write('probability color=black: '),writeln(P).  % exact 0.1

nballs ~ uniform([1,2,3,4,5,6,7,8,9,10]).

test_balls(N) :-
	init,
	query([],[],nballs ~= 4,N,P),
	query([],[],(nballs ~= NB,NB>5),N,P2),
	write('probability nballs=4: '),writeln(P),     % exact 0.1
	write('probability nballs>5: '),writeln(P2).    % exact 0.5

ball(X) := nballs ~= N, between(1,N,X).

material(X) ~ finite([0.3:wood,0.7:metal]) := ball(X).

color(X) ~ uniform([grey,blue,black]) := material(X) ~= metal.
color(X) ~ uniform([black,brown]) := material(X) ~= wood.

drawn(_) ~ uniform(Balls) := nballs ~= N, findall(X,between(1,N,X),Balls).

size(X) ~ beta(2,3) := material(X) ~= metal.
size(X) ~ beta(4,2) := material(X) ~= wood.

test_balls2(N) :-
	init,
	query([],[],(drawn(1) ~= X,color(X)~=black),N,P),
	write('probability first drawn ball is black: '),writeln(P).   % exact 0.7/3+0.3/2 = 0.383333
