%%% -*- Mode: Prolog; -*-
% The Indian GPA problem (the original's indian-gpa.pl) with its options
% (query propagation) and its test predicate.  This engine propagates the
% evidence with the Jacobian of V is A*4.0 (resp. A*10.0), so its answers are
% the correct 0.611 (gpa 3.0) and 0.374 (gpa 3.9); the original printed
% 0.385 and 0.193.  gpa 4.0 gives 1.0 in both (a point mass beats a density).
%   swipl -g "test_gpa(10000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/indian_gpa.pl

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_query_propagation(true),set_inference(backward(lw)).
:- initialization(init).

coin ~ finite([0.95:true,0.05:false]).
agpa ~ beta(8,2) := coin ~= true.
american_gpa ~ finite([0.85:4.0,0.15:0.0]) := coin ~= false.
american_gpa ~ val(V) := agpa ~= A, V is A*4.0.

coin2 ~ finite([0.99:true,0.01:false]).
igpa ~ beta(5,5) := coin2 ~= true.
indian_gpa ~ finite([0.1:0.0,0.9:10.0]) := coin2 ~= false.
indian_gpa ~ val(V) := igpa ~= A, V is A*10.0.

nation ~ finite([0.25:a,0.75:i]).
student_gpa ~ val(A) := nation ~= a, american_gpa ~= A.
student_gpa ~ val(A) := nation ~= i, indian_gpa ~= A.

test_gpa(N) :-
	init,
	query([student_gpa ~= 3.0],[],nation ~= a,N,P1),
	write('p(nation=a|student_gpa=3.0): '),writeln(P1),
	query([student_gpa ~= 3.9],[],nation ~= a,N,P2),
	write('p(nation=a|student_gpa=3.9): '),writeln(P2),
	query([student_gpa ~= 4.0],[],nation ~= a,N,P3),
	write('p(nation=a|student_gpa=4.0): '),writeln(P3).
