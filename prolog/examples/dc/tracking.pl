%%% -*- Mode: Prolog; -*-
% 3-D object tracking with the original DCPF (its tracking.pl), in the
% original's style: the dcpf header, builtin/1 declarations, an object born
% at its first observation, constant-position dynamics with the
% motion-model covariance of cov/3, and observation steps whose proposal
% is the Kalman posterior (logIndepOptimalProposals) and whose weight is
% the predictive density read back through logfinite([W:_]).
%   swipl -g "test_tracking(1000)" -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/tracking.pl
%
% Exact answers (cov(1,...) with varQ 0.005, deltaT 0.2: the position
% variance 0.0002, measurement variance 0.001):
%   after the birth step (observation (0.6,1,0)): each coordinate of the
%   position ~ N(obs, 0.0002), mean (0.6,1,0), sd 0.01414;
%   after a second observation (0.7,1,0) with no action: the position
%   prior at t+1 is N(0.6, 0.0002+0.0002) in x, so the posterior mean is
%   0.6 + 0.0004/0.0014*0.1 = 0.628571 (y stays 1, z stays 0) and its
%   variance 0.0004*0.001/0.0014 = 0.000285714.

:- use_module('../dcpf.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).

builtin(deltaT(_)).
builtin(varQ(_)).
builtin(cov(_,_,_)).
builtin(dim(_,_)).
builtin(rgbcolor(_,_)).

:- set_options(default).

deltaT(0.2).
varQ(0.005).

% motion-model covariance of one coordinate block (position, velocity):
% the position variance varQ*deltaT^2, the velocity kept (almost) fixed
cov(1,[Cov,0,0,0.0000001],VarQ) :-
	deltaT(DeltaT),
	Cov is VarQ*DeltaT^2.

dim(1,(0.02,0.02,0.02)).
dim(2,(0.20,0.255,0.155)).
rgbcolor(1,(0.0,1.0,0.0)).
rgbcolor(2,(0.8,0.5,0.1)).

% birth: an object not tracked yet appears where it is first observed
object(ID):t+1 ~ indepGaussians([ ([X,0],Cov), ([Y,0],Cov), ([Z,0],Cov) ]) :=
	observation(object(ID)) ~= (X,Y,Z),
	\+(object(ID):t ~= _),
	varQ(VarQ),
	cov(1,Cov,VarQ).

% unobserved, moved by the action
object(ID):t+1 ~ indepGaussians([ ([NX,0],Cov), ([NY,0],Cov), ([Z,0],Cov) ]) :=
	object(ID):t ~= (X,_,Y,_,Z,_),
	\+(observation(object(ID)) ~= _),
	action(move(ID,DX,DY)),
	NX is X+DX,
	NY is Y+DY,
	varQ(VarQ),
	cov(1,Cov,VarQ).

% unobserved, not moved
object(ID):t+1 ~ indepGaussians([ ([X,0],Cov), ([Y,0],Cov), ([Z,0],Cov) ]) :=
	object(ID):t ~= (X,_,Y,_,Z,_),
	\+(observation(object(ID)) ~= _),
	\+(action(move(ID,_,_))),
	varQ(VarQ),
	cov(1,Cov,VarQ).

% observed: the state is the optimal proposal's draw
object(ID):t+1 ~ val(V) :=
	objectProposal(ID):t+1 ~= [V|_].

% the optimal proposal: per coordinate the Kalman posterior of the
% predicted block ([Mean,0],Cov) given the measured position (H = [1,0],
% measurement variance 0.001), with the log predictive density
objectProposal(ID):t+1 ~ logIndepOptimalProposals([
			([NX,0],Cov,[1,0],[0.001],[OX]),
			([NY,0],Cov,[1,0],[0.001],[OY]),
			([Z,0],Cov,[1,0],[0.001],[OZ])]) :=
	object(ID):t ~= (X,_,Y,_,Z,_),
	observation(object(ID)) ~= (OX,OY,OZ),
	action(move(ID,DX,DY)),
	NX is X+DX,
	NY is Y+DY,
	varQ(VarQ),
	cov(1,Cov,VarQ).

objectProposal(ID):t+1 ~ logIndepOptimalProposals([
			([X,0],Cov,[1,0],[0.001],[OX]),
			([Y,0],Cov,[1,0],[0.001],[OY]),
			([Z,0],Cov,[1,0],[0.001],[OZ])]) :=
	object(ID):t ~= (X,_,Y,_,Z,_),
	observation(object(ID)) ~= (OX,OY,OZ),
	\+(action(move(ID,_,_))),
	varQ(VarQ),
	cov(1,Cov,VarQ).

% observation model: the particle is weighed by the proposal's predictive
% density W = [LogW] (the original's one-entry logfinite)
observation(object(ID)):t+1 ~ logfinite([W:_]) :=
	objectProposal(ID):t+1 ~= [_|W].

% the first observation of an object weighs every particle alike
observation(object(ID)):t+1 ~ finite([1:_]) :=
	\+(object(ID):t ~= _).

% weighted mean tracked position of object ID over the particles
averageposition(ID,N,(MX,MY,MZ)) :-
	eval_query_particle2((X,Y,Z),current(object(ID)) ~= (X,_,Y,_,Z,_),N,L),
	weightedmean(L,MX,MY,MZ).

weightedmean(L,MX,MY,MZ) :-
	findall(P,member(P:_,L),Ps), sum_list(Ps,S),
	findall(PX,(member(P:(X,_,_),L),PX is P*X),PXs), sum_list(PXs,SX),
	findall(PY,(member(P:(_,Y,_),L),PY is P*Y),PYs), sum_list(PYs,SY),
	findall(PZ,(member(P:(_,_,Z),L),PZ is P*Z),PZs), sum_list(PZs,SZ),
	MX is SX/S, MY is SY/S, MZ is SZ/S.

test_tracking(N) :-
	init_particle(N),
	dcpf:step_particle_aux([],[observation(object(1)) ~= (0.6,1,0)],[],N,0.2),
	averageposition(1,N,P1),
	write('after the first observation (0.6,1,0): '),write(P1),nl,
	dcpf:step_particle_aux([],[observation(object(1)) ~= (0.7,1,0)],[],N,0.2),
	averageposition(1,N,P2),
	write('after the second observation (0.7,1,0), exact (0.628571,1,0): '),write(P2),nl,
	plotdata(N).

search_query(I,Q) :-
	distributionalclause:proof_query_backward(I,Q).

% data.txt: one line per particle, "ID X Y Z R G B"
plotdata(N) :-
	dcpf:bb_get(offset,Offset),
	open('data.txt','write',S),
	(   between(1,N,Pos),
	    I is Offset+Pos,
	    search_query(I,current(object(ID)) ~= (X,_,Y,_,Z,_)),
	    rgbcolor(ID,(R,G,B)),
	    write(S,ID),write(S,' '),
	    write(S,X),write(S,' '),write(S,Y),write(S,' '),write(S,Z),write(S,' '),
	    write(S,R),write(S,' '),write(S,G),write(S,' '),write(S,B),nl(S),
	    fail
	;   true
	),
	nl(S),
	close(S).
