%%% -*- Mode: Prolog; -*-
% Generating worlds with the original DC (its generatesamples.pl), in the
% original's style: church's coin, a product of two gaussians, and one
% step of a 3-D object's motion model proven backward from a world that
% already holds the object's position and an action (generate_backward/3).
% move(ID,DX,DY) shifts object ID by (DX,DY), so move(1,1,0) from (0,0,0)
% gives next(object(1)) ~ (1,0,0) with variance varQ*deltaT^2 = 0.0004 per
% coordinate (standard deviation 0.02).
%   swipl -g "test_object(2000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/generatesamples.pl

:- use_module('../distributionalclause.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

:- set_options(default),set_inference(backward(lw)).

:- initialization(init).

builtin(deltaT(_)).
builtin(varQ(_)).
builtin(cov(_,_,_)).

deltaT(1).
varQ(0.0004).

% the covariance of a position block after deltaT (constant velocity)
cov(1,[Cov],VarQ) :-
	deltaT(DeltaT),
	Cov is VarQ*DeltaT^2.

% church: (hist (repeat 1000 flip) "Flips")
coin ~ finite([0.5:true,0.5:false]).

% N is the number of samples
test_coin(N) :-
	init,
	eval_query([],[],coin ~= true,N,P,_,_),
	write('probability coin=true (exact 0.5): '),writeln(P).

% not memoised: a fresh flip at each call
test_coin2(N) :-
	init,
	eval_query([],[],true(0.5),N,P,_,_),
	write('probability fair coin=true (exact 0.5): '),writeln(P).

% church: (* (gaussian 0 1) (gaussian 0 1) )
g ~ gaussian(0,1).
g2 ~ gaussian(0,1).
prod ~ val(P) :=
	g ~= Val1,
	g2 ~= Val2,
	P is Val1*Val2.

test_prod :-
	init,
	generate_backward(prod ~= _,L),
	writeln(L).

% one world of the motion model, from a world holding object 1 at the
% origin and the action move(1,1,0)
test :-
	generate_backward([current(object(1))~=(0,0,0),action(move(1,1,0))],next(object(1)) ~= V,L),
	writeln(V),
	writeln(L).

% the mean and standard deviation of next(object(1)) over N worlds
test_object(N) :-
	init,
	findall(V,(between(1,N,_),generate_backward([current(object(1))~=(0,0,0),action(move(1,1,0))],next(object(1)) ~= V,_)),Vs),
	findall(X,member((X,_,_),Vs),Xs),
	findall(Y,member((_,Y,_),Vs),Ys),
	findall(Z,member((_,_,Z),Vs),Zs),
	mean_sd(Xs,MX,SX),mean_sd(Ys,MY,SY),mean_sd(Zs,MZ,SZ),
	writeln('exact mean (1,0,0), standard deviation 0.02'),
	format('mean (~4f,~4f,~4f), standard deviation (~4f,~4f,~4f)~n',[MX,MY,MZ,SX,SY,SZ]).

mean_sd(L,M,S) :-
	length(L,N),
	sum_list(L,Sum),
	M is Sum/N,
	findall(D,(member(X,L),D is (X-M)^2),Ds),
	sum_list(Ds,SD),
	S is sqrt(SD/(N-1)).

object(ID):t+1 ~ indepGaussians([ ([NX],Cov), ([NY],Cov), ([0],Cov) ]) :=
	object(ID):t ~= (X,Y,Z),
	\+observation(object(ID)) ~=_,
	action(move(ID,DX,DY)),
	NX is X+DX,
	NY is Y+DY,
	varQ(VarQ),
	cov(1,Cov,VarQ).

object(ID):t+1 ~ indepGaussians([ ([X],Cov), ([Y],Cov), ([Z],Cov) ]) :=
	object(ID):t ~= (X,Y,Z),
	\+observation(object(ID)) ~=_,
	\+action(move(ID,_,_)),
	varQ(VarQ),
	cov(1,Cov,VarQ).
