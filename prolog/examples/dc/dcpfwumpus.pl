%%% -*- Mode: Prolog; -*-
% The wumpus maze of the original DCPF (its dcpfwumpus.pl), in the
% original's style: the dcpf header, builtin/1 declarations, h:t beliefs
% guarded by belief/1, and a test predicate over init_particle/1,
% step_particle/5 and eval_query_particle/3.
%   swipl -g "test1(2000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/dcpfwumpus.pl

:- use_module('../dcpf.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

builtin(checkvalue(_,_)).
builtin(\+A) :-
	builtin(A).
builtin(write(_)).

checkvalue(true,1.0).
checkvalue(false,0.0).

:- set_options(default).

% the belief at time t of a cell not seen yet
maze(X,Y):t ~ finite([0.0:pit,0.6:free,0.4:wall]) := belief(maze(X,Y)),between(-3,3,X),between(-3,3,Y),(X,Y)\=(0,0).
maze(0,0):t ~ uniform([free]) := true.

position:0 ~ finite([1:(0,0)]) := true.

maze(X,Y):t+1 ~ finite([1:Val]) :=
	maze(X,Y):t ~= Val.

position:t+1 ~ finite([0.1:(Xold,Yold),0.9:(X,Yold)]) :=
	position:t ~= (Xold,Yold), action(left), X is Xold - 1, \+(maze(X,Yold):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(left), X is Xold - 1, maze(X,Yold):t ~= wall.
position:t+1 ~ finite([0.1:(Xold,Yold),0.9:(X,Yold)]) :=
	position:t ~= (Xold,Yold), action(right), X is Xold + 1, \+(maze(X,Yold):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(right), X is Xold + 1, maze(X,Yold):t ~= wall.
position:t+1 ~ finite([0.1:(Xold,Yold),0.9:(Xold,Y)]) :=
	position:t ~= (Xold,Yold), action(up), Y is Yold + 1, \+(maze(Xold,Y):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(up), Y is Yold + 1, maze(Xold,Y):t ~= wall.
position:t+1 ~ finite([0.1:(Xold,Yold),0.9:(Xold,Y)]) :=
	position:t ~= (Xold,Yold), action(down), Y is Yold - 1, \+(maze(Xold,Y):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(down), Y is Yold - 1, maze(Xold,Y):t ~= wall.
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(null).

observation(up):t+1 ~ finite([0.9:free,0.1:wall]) :=
	position:t+1 ~= (X,Y), Ynext is Y + 1, maze(X,Ynext):t+1 ~= free.
observation(up):t+1 ~ finite([0.9:wall,0.1:free]) :=
	position:t+1 ~= (X,Y), Ynext is Y + 1, maze(X,Ynext):t+1 ~= wall.
observation(down):t+1 ~ finite([0.9:free,0.1:wall]) :=
	position:t+1 ~= (X,Y), Ynext is Y - 1, maze(X,Ynext):t+1 ~= free.
observation(down):t+1 ~ finite([0.9:wall,0.1:free]) :=
	position:t+1 ~= (X,Y), Ynext is Y - 1, maze(X,Ynext):t+1 ~= wall.
observation(left):t+1 ~ finite([0.9:free,0.1:wall]) :=
	position:t+1 ~= (X,Y), Xnext is X - 1, maze(Xnext,Y):t+1 ~= free.
observation(left):t+1 ~ finite([0.9:wall,0.1:free]) :=
	position:t+1 ~= (X,Y), Xnext is X - 1, maze(Xnext,Y):t+1 ~= wall.
observation(right):t+1 ~ finite([0.9:free,0.1:wall]) :=
	position:t+1 ~= (X,Y), Xnext is X + 1, maze(Xnext,Y):t+1 ~= free.
observation(right):t+1 ~ finite([0.9:wall,0.1:free]) :=
	position:t+1 ~= (X,Y), Xnext is X + 1, maze(Xnext,Y):t+1 ~= wall.

test1(N) :-
	init_particle(N),
	step_particle([action(null)],[observation(up) ~= wall,observation(right) ~= free],[],N,1),
	eval_query_particle(current(maze(0,1))~=wall,N,P),
	Error is abs(0.857142857142857-P),
	write('P(maze(0,1)=wall): '),writeln(P),
	write('absolute error '),writeln(Error).

mazesizemin(-2).
mazesizemax(2).

% one particle's maze, as the original's plotdata/1 drew it
plotdata(Pos) :-
	bb_get(dcpf:offset,Offset),
	I is Offset+Pos,
	mazesizemin(Min),
	mazesizemax(Max),
	(   between(Min,Max,YY),
	    Y is Max+Min-YY,
	    (   between(Min,Max,X),
	        (   distributionalclause:proof_query_backward(I,current(position) ~= (X,Y)) -> write('AA')
	        ;   distributionalclause:proof_query_backward(I,current(maze(X,Y)) ~= V), V == wall -> write('##')
	        ;   write('  ')
	        ),
	        fail
	    ;   true
	    ),
	    nl,
	    fail
	;   true
	).
