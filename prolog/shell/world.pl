/** <module> Ask a saved world model questions by hand

Usage:  swipl prolog/shell/world.pl OUT/world.pl      (or: anchoring shell OUT)

The world file (written by `anchoring run`) holds plain facts in module user: anchors
(anchor/5), their attributes (attribute/3) and the particle set of the filter
(particle/2, particle_fact/2), and which frame it is after (world_frame(Frame, Time));
see python/probanchor/loop/world_file.py.  Both files
given to swipl are loaded, so the facts can also be asked directly
(?- anchor(A, S, C, Seen, T).).
Examples:

    ?- anchors(As).
    ?- where(ball_1, Mean, Spread).
    ?- prob(occluded_by(ball_1, mug_1), P).
    ?- occluders(ball_1, Dist).
    ?- hidden_under(Obj, Occ, P).
    ?- prob((pos(ball_1, (X,_,_)), X > 0.1), P).
    ?- prob(identity(percept(141, 0), ball_1), P).
    ?- ambiguous(Percept, Dist).
*/

:- module(anchoring_world,
          [ load_world/1,       % +File
            anchors/1,          % -Atoms
            prob/2,             % :Goal, -P
            where/3,            % +Atom, -Mean, -Spread
            occluders/2,        % +Atom, -Dist
            hidden_under/3,     % ?Object, ?Occluder, -P
            ambiguous/2,        % ?Percept, -Dist
            banner/0
          ]).

:- use_module(library(aggregate)).
:- use_module(library(lists)).
:- use_module(library(apply)).

:- dynamic user:anchor/5, user:attribute/3, user:particle/2, user:particle_fact/2,
   user:identity/3, user:world_frame/2.

%!  load_world(+File) is det.
%
%   Load (or reload) a world file into module user, replacing the world loaded before.
load_world(File) :-
    retractall(user:anchor(_, _, _, _, _)),
    retractall(user:attribute(_, _, _)),
    retractall(user:particle(_, _)),
    retractall(user:particle_fact(_, _)),
    retractall(user:identity(_, _, _)),
    retractall(user:world_frame(_, _)),
    load_files(user:File, [if(true)]).

%!  anchors(-Atoms) is det.
%
%   The atoms of all anchors in the world, in the order they were written.
anchors(As) :-
    findall(A, user:anchor(A, _, _, _, _), As).

%!  prob(:Goal, -P) is det.
%
%   The weighted fraction of particles in which Goal holds.  Goal is a conjunction of
%   particle facts (pos(Atom, (X,Y,Z)), occluded_by(Atom, Occ)) and Prolog tests.  Every
%   anchor the filter knows has a position in every particle; perceived ones are tight
%   around the perceived position.
%
%   identity(percept(Frame, Index), Atom) is the probability that the Index-th percept of
%   frame Frame was the anchor Atom, for the re-acquisitions the run reported ambiguous
%   (identity/3 facts: nothing it saw told Atom from a look-alike there); 0 for an anchor that
%   was no candidate.
%
%   @error existence_error(ambiguous_percept, Percept) if Percept was not ambiguous.
prob(identity(Percept, A), P) :-
    !,
    (   user:identity(Percept, _, _)
    ->  (   user:identity(Percept, A, P0) -> P = P0 ; P = 0.0 )
    ;   existence_error(ambiguous_percept, Percept)
    ).
prob(Goal, P) :-
    aggregate_all(sum(W), user:particle(_, W), Total),
    (   Total =:= 0
    ->  P = 0.0
    ;   aggregate_all(sum(W), (user:particle(I, W), \+ \+ holds(I, Goal)), Sum),
        P is Sum / Total
    ).

holds(I, (A, B)) :- !, holds(I, A), holds(I, B).
holds(I, \+ G) :- !, \+ holds(I, G).
holds(I, pos(A, P)) :- !, user:particle_fact(I, pos(A, P)).
holds(I, occluded_by(A, O)) :- !, user:particle_fact(I, occluded_by(A, O)).
holds(_, G) :- call(user:G).

%!  where(+Atom, -Mean, -Spread) is semidet.
%
%   The weighted mean position (X,Y,Z) of Atom over the particles and the root mean square
%   distance of the particles from it (metres).
where(A, (MX, MY, MZ), Spread) :-
    findall(W-(X, Y, Z), (user:particle(I, W), user:particle_fact(I, pos(A, (X, Y, Z)))), L),
    L \== [],
    foldl([W-(X, Y, Z), s(S0, X0, Y0, Z0), s(S1, X1, Y1, Z1)]>>(
              S1 is S0+W, X1 is X0+W*X, Y1 is Y0+W*Y, Z1 is Z0+W*Z),
          L, s(0, 0, 0, 0), s(S, SX, SY, SZ)),
    S > 0,
    MX is SX/S, MY is SY/S, MZ is SZ/S,
    foldl([W-(X, Y, Z), V0, V1]>>(V1 is V0 + W*((X-MX)**2 + (Y-MY)**2 + (Z-MZ)**2)),
          L, 0, V),
    Spread is sqrt(V/S).

%!  occluders(+Atom, -Dist) is det.
%
%   Dist is a list P-Occluder, most probable first, over the particles.
occluders(A, Dist) :-
    findall(O, user:particle_fact(_, occluded_by(A, O)), Os0),
    sort(Os0, Os),
    findall(P-O, (member(O, Os), prob(occluded_by(A, O), P)), D0),
    sort(1, @>=, D0, Dist).

%!  hidden_under(?Object, ?Occluder, -P) is nondet.
%
%   Object is believed under Occluder with probability P > 0.
hidden_under(A, O, P) :-
    findall(A-O, user:particle_fact(_, occluded_by(A, O)), Pairs0),
    sort(Pairs0, Pairs),
    member(A-O, Pairs),
    prob(occluded_by(A, O), P),
    P > 0.

%!  ambiguous(?Percept, -Dist) is nondet.
%
%   Percept (percept(Frame, Index)) was re-acquired ambiguously; Dist is a list P-Atom of the
%   candidates, most probable first (the first is the symbol it was given).
ambiguous(Percept, Dist) :-
    findall(Pc, user:identity(Pc, _, _), Ps0),
    sort(Ps0, Ps),
    member(Percept, Ps),
    findall(P-A, user:identity(Percept, A, P), D0),
    sort(1, @>=, D0, Dist).

%!  banner is det.
%
%   Print what the loaded world holds and a few questions to try.
banner :-
    anchors(As),
    length(As, N),
    (   user:world_frame(F, T)        % which frame the world model is after
    ->  format("World model after frame ~d (~3f s): ~d anchors ~w.~n", [F, T, N, As])
    ;   format("World model: ~d anchors ~w.~n", [N, As])
    ),
    format("Try: prob(occluded_by(ball_1, mug_1), P).  occluders(ball_1, D).  \
where(ball_1, Mean, Spread).~n").
