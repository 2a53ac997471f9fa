%%% -*- Mode: Prolog; -*-
% A probabilistic graph in the style of the original's exampleproblog.pl:
% each edge exists with probability 0.5, p/2 is reachability over the edges
% that exist, path/2 plain Prolog over a fixed graph.
%   swipl -g "test(10000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/exampleproblog.pl

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_query_propagation(true),set_inference(backward(lw)).

e(1,2) ~ finite([0.5:true,0.5:false]).
e(1,6) ~ finite([0.5:true,0.5:false]).
e(2,3) ~ finite([0.5:true,0.5:false]).
e(3,4) ~ finite([0.5:true,0.5:false]).
e(6,5) ~ finite([0.5:true,0.5:false]).

p(X,Y) := e(X,Y) ~= true.
p(X,Y) := e(X,Z) ~= true, p(Z,Y).

edge(1,2). edge(1,6). edge(2,3). edge(3,4). edge(6,5).
path(X,Y) :- edge(X,Y).
path(X,Y) :- edge(X,Z), path(Z,Y).

test(N) :-
	init,
	query([],[],p(1,4),N,P1),
	write('p(1,4): '),writeln(P1),          % exact 0.125
	query([],[],p(1,5),N,P2),
	write('p(1,5): '),writeln(P2),          % exact 0.25
	query([],[],path(1,5),N,P3),
	write('path(1,5): '),writeln(P3),       % 1.0
	generate_backward(p(1,5),L),
	write('one world: '),writeln(L).
