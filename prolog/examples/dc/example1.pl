%%% -*- Mode: Prolog; -*-
% The original DC system's example1 (its README's test), in the original's
% style: query/7, query/8 (averages), test_query/6, and `X is random`.
% Loading it in swipl runs test(10000), as the original did:
%   swipl -g halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/example1.pl

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_inference(backward(lw)).

nballs ~ uniform([1,2,3,4,5,6,7,8,9,10]) := true.
n2 ~ finite([0.9:1,0.05:5,0.05:6]) := true.
n3 ~ poisson(4) := true.
n4 ~ uniform([2,N]) := n2~=N.
ball(X) := nballs ~= N, between(1,N,X).
n3 := n2 ~= 1, true(0.5).
n3_1 := n2 ~= 1, sample(contUniform(0,1),X), X<0.5.
n3_2 := n2 ~= 1, X is random, X<0.5.        % the original's arithmetic
drawn(_) ~ uniform(Balls) := nballs ~= N, findall(X,between(1,N,X),Balls).
g ~ gaussian(0,0.01) := true.
g2 ~ gaussian(X,0.01) := g ~= X.

harmonic(From,S) :- findall(1/K,between(From,10,K),L), sumlist(L,S).

test(N) :-
	init,
	query([],[],drawn(1) ~= 1,N,P1,_,_),
	harmonic(1,H1), E1 is abs(P1-0.1*H1),
	write('Absolute error drawn(1) ~= 1: '),writeln(E1),
	query([],[],drawn(1) ~= 2,N,P2,_,_),
	harmonic(2,H2), E2 is abs(P2-0.1*H2),
	write('Absolute error drawn(1) ~= 2: '),writeln(E2),
	query([],[],drawn(1) ~= 3,N,P3,_,_),
	harmonic(3,H3), E3 is abs(P3-0.1*H3),
	write('Absolute error drawn(1) ~= 3: '),writeln(E3),
	query([],[],g ~= A,A,N,P0,_,_),
	E0 is abs(0.0-P0),
	write('Absolute error average g: '),writeln(E0).

testpoisson(N) :-
	init,
	test_query([],[],n3 ~= 4,1,N,_).            % exact 0.195367

test_random(N) :-
	init,
	query([],[],n3,N,P1,_,_),
	query([],[],n3_2,N,P2,_,_),
	write('n3: '),writeln(P1),                  % exact 0.45
	write('n3_2: '),writeln(P2).                % exact 0.45

test2(N) :-
	init,
	query([],[],(g ~= A,A<0.0),N,P,_,_),
	write('g<0.0: '),writeln(P),                % exact 0.5
	query([],[],(g ~= A,A>0,A<0.1),N,P2,_,_),
	write('0.0<g<0.1: '),writeln(P2),           % exact 0.341345
	query([(g ~= A,A>0)],[],(g ~= A,A<0.1),N,P3,_,_),
	write('g<0.1 | g>0.0: '),writeln(P3),       % exact 0.68269
	query([],[],(g ~= 0.0),N,P4,_,_),
	write('density g=0.0: '),writeln(P4),       % exact 3.98942280401433
	query([],[],(g2 ~= 0.0),N,P5,_,_),
	write('density g2=0.0: '),writeln(P5),      % exact 2.82094791773878
	query([g~=0.1],[],(g2 ~= 0.1),N,P6,_,_),
	write('density g2=0.1|g=0.1: '),writeln(P6).   % exact 3.98942280401433

:- initialization(time(test(10000))).
