%%% -*- Mode: Prolog; -*-
% Data association with one particle in the original DCPF (its
% minimalexample.pl), in the original's style: anchors observed as new
% (a) or re-observed (r); an object is created for a new anchor when none
% exists, kept for a re-observed one, and an unobserved object is
% associated with one of the objects of the unobserved anchors
% (findall_forward/3 over current(object(A)) ~= O in the body).  Its
% plotdata/1 writes the "Anchor Object" lines to data.txt through the
% original's internals (eraseall/1, proof_query_backward_lazy/3).
%   swipl -g t2 -t halt prolog/ddc/compat/dc_compat.pl prolog/examples/dc/minimalexample.pl
%
% What the tests write (one particle, no randomness left):
%   t2: anchor2 anchor2         (anchor3 arrives when an object exists: no
%                                clause creates one for it)
%   t3: anchor1 anchor1, anchor2 anchor2
% t1 is the original's "not okay" case.

:- use_module('../dcpf.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).
:- set_options(default).

% an unobserved object goes with one of the unobserved anchors' objects
% (none: no association; uniform([]) is an error here)
associate:t+1 ~ uniform(Objects) :=
	observation(anchor(_)) ~= _,
	findall_forward(O, (current(object(A)) ~= O, \+(observation(anchor(A)) ~= _)), Objects),
	Objects \== [],
	writeln(Objects).

% a new anchor with no object yet: its own object
object(Anchor):t+1 ~ val(Anchor) :=
	observation(anchor(Anchor)) ~= a,
	\+(object(_):t ~= _).
% a re-observed anchor keeps its object
object(Anchor):t+1 ~ val(Object) :=
	observation(anchor(Anchor)) ~= r,
	object(Anchor):t ~= Object.
% an unobserved anchor, while others are observed
object(A):t+1 ~ val(Object) :=
	current(object(A)) ~= _,
	\+(observation(anchor(A)) ~= _),
	observation(anchor(_)) ~= _,
	associate:t+1 ~= Object.

observation(anchor(_)):t+1 ~ val(_) :=
	true.

t1 :- % the original's "not okay"
	N = 1,
	init_particle(N),
	step_particle([],[observation(anchor(anchor1)) ~= a, observation(anchor(anchor2)) ~= a],N,1),
	step_particle([],[observation(anchor(anchor1)) ~= r, observation(anchor(anchor3)) ~= a],N,1),
	plotdata(N).

t2 :-
	N = 1,
	init_particle(N),
	step_particle([],[observation(anchor(anchor2)) ~= a],N,1),
	step_particle([],[observation(anchor(anchor3)) ~= a],N,1),
	plotdata(N).

t3 :-
	N = 1,
	init_particle(N),
	step_particle([],[observation(anchor(anchor1)) ~= a, observation(anchor(anchor2)) ~= a],N,1),
	step_particle([],[observation(anchor(anchor1)) ~= r],N,1),
	plotdata(N).

search_query(I,Q) :-
	eraseall(tempparticle),
	abolish_all_tables,
	distributionalclause:proof_query_backward_lazy(I,tempparticle,Q).

% data.txt: "Anchor Object", one line per object of each particle
plotdata(N) :-
	dcpf:bb_get(offset,Offset),
	open('data.txt','write',S),
	(   between(1,N,Pos),
	    I is Offset+Pos,
	    search_query(I,current(object(Anchor)) ~= Object),
	    write(S,Anchor),write(S,' '),write(S,Object),nl(S),
	    fail
	;   true
	),
	nl(S),
	close(S).
