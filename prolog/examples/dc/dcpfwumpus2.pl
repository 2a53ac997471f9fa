%%% -*- Mode: Prolog; -*-
% The pit world of the original DCPF (its dcpfwumpus2.pl), in the
% original's style: cells free (0.8) or a pit (0.2), walls outside the
% quadrant, deterministic moves, a breeze next to a pit (four clauses that
% may all apply: as in the original, the first one whose body holds counts).  unittest/0 runs
% four steps over 10,000 particles and prints the joint of three cells
% against the exact one, and eval_query_particle2/4's marginals.
%   swipl -g unittest -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/dcpfwumpus2.pl

:- use_module('../dcpf.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

builtin(ground(_)).

:- set_options(default).

maze(X,Y):t ~ finite([0.8:free,0.2:pit]) := ground(X),ground(Y),X>=0,Y>=0,(X,Y)\=(0,0).
maze(X,Y):t ~ finite([1:wall]) := ground(X),ground(Y),X<0.
maze(X,Y):t ~ finite([1:wall]) := ground(X),ground(Y),Y<0.
maze(0,0):t ~ uniform([free]) := true.

position:0 ~ finite([1:(0,0)]) := true.

maze(X,Y):t+1 ~ finite([1:Val]) :=
	maze(X,Y):t ~= Val.

position:t+1 ~ finite([1:(X,Yold)]) :=
	position:t ~= (Xold,Yold), action(left), X is Xold - 1, \+(maze(X,Yold):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(left), X is Xold - 1, maze(X,Yold):t ~= wall.
position:t+1 ~ finite([1:(X,Yold)]) :=
	position:t ~= (Xold,Yold), action(right), X is Xold + 1, \+(maze(X,Yold):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(right), X is Xold + 1, maze(X,Yold):t ~= wall.
position:t+1 ~ finite([1:(Xold,Y)]) :=
	position:t ~= (Xold,Yold), action(up), Y is Yold + 1, \+(maze(Xold,Y):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(up), Y is Yold + 1, maze(Xold,Y):t ~= wall.
position:t+1 ~ finite([1:(Xold,Y)]) :=
	position:t ~= (Xold,Yold), action(down), Y is Yold - 1, \+(maze(Xold,Y):t ~= wall).
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(down), Y is Yold - 1, maze(Xold,Y):t ~= wall.
position:t+1 ~ finite([1:(Xold,Yold)]) :=
	position:t ~= (Xold,Yold), action(null).

observation(breeze):t+1 ~ finite([1.0:true,0.0:false]) :=
	position:t+1 ~= (X,Y), Xnext is X + 1, maze(Xnext,Y):t+1 ~= pit.
observation(breeze):t+1 ~ finite([1.0:true,0.0:false]) :=
	position:t+1 ~= (X,Y), Xnext is X - 1, maze(Xnext,Y):t+1 ~= pit.
observation(breeze):t+1 ~ finite([1.0:true,0.0:false]) :=
	position:t+1 ~= (X,Y), Ynext is Y + 1, maze(X,Ynext):t+1 ~= pit.
observation(breeze):t+1 ~ finite([1.0:true,0.0:false]) :=
	position:t+1 ~= (X,Y), Ynext is Y - 1, maze(X,Ynext):t+1 ~= pit.
observation(breeze):t+1 ~ finite([1.0:false,0.0:true]) :=
	position:t+1 ~= (X,Y), Xnext is X + 1, Ynext is Y + 1, Xprec is X - 1, Yprec is Y - 1,
	\+(maze(Xnext,Y):t+1 ~= pit), \+(maze(X,Ynext):t+1 ~= pit), \+(maze(Xprec,Y):t+1 ~= pit), \+(maze(X,Yprec):t+1 ~= pit).

unittest :-
	kl(10000,KL,Diff),
	write('KL '),writeln(KL),
	write('total absolute difference '),writeln(Diff),
	eval_query_particle2((X,Y),current(maze(X,Y)) ~= free,10000,L),
	writeln('exact [1.0:(0,0),1.0:(0,1),0.689655:(0,2),1.0:(1,0),0.137931:(1,1),0.689655:(2,0)]'),
	write(' Got: '),writeln(L).

kl(Particles,KL,Diff) :-
	init_particle(Particles),
	step_particle([action(null)],[observation(breeze) ~= false],Particles),
	step_particle([action(up)],[observation(breeze) ~= true],Particles),
	step_particle([action(down)],[observation(breeze) ~= false],Particles),
	step_particle([action(right)],[observation(breeze) ~= true],Particles),
	eval_query_particle((current(maze(0,2))~=pit,current(maze(1,1))~=pit,current(maze(2,0))~=pit),Particles,W1),
	eval_query_particle((current(maze(0,2))~=pit,current(maze(1,1))~=pit,current(maze(2,0))~=free),Particles,W2),
	eval_query_particle((current(maze(0,2))~=pit,current(maze(1,1))~=free,current(maze(2,0))~=pit),Particles,W3),
	eval_query_particle((current(maze(0,2))~=free,current(maze(1,1))~=pit,current(maze(2,0))~=pit),Particles,W4),
	eval_query_particle((current(maze(0,2))~=free,current(maze(1,1))~=pit,current(maze(2,0))~=free),Particles,W5),
	KL is 0.034482759*log(0.034482759/W1)+0.137931034*log(0.137931034/W2)+0.137931034*log(0.137931034/W3)
	    +0.137931034*log(0.137931034/W4)+0.551724138*log(0.551724138/W5),
	Diff is abs(0.034482759-W1)+abs(0.137931034-W2)+abs(0.137931034-W3)+abs(0.137931034-W4)+abs(0.551724138-W5),!.
