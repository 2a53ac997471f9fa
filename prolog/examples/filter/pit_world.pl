% The pit world, four filtering steps (a re-statement of the original DCPF example
% dcpfwumpus2.pl, dc-reference section 4, in this project's own words).
%
% Cells with X < 0 or Y < 0 are walls, (0,0) is free, every other cell holds a pit with
% probability 0.2.  Moves are deterministic.  After each step the agent feels a breeze
% exactly when a pit is next to it.  The cells never change: the persistence clause below
% says so explicitly (the original copied the time-t prior into the transition, which could
% redraw a cell; here nothing is copied unless written).
%
% Conformance targets after  null/no breeze, up/breeze, down/no breeze, right/breeze
% (see pit_world.jsonl), over (maze(0,2), maze(1,1), maze(2,0)):
%   (pit,pit,pit) 1/29 = 0.0345; (pit,pit,free), (pit,free,pit), (free,pit,pit) 4/29 = 0.1379;
%   (free,pit,free) 16/29 = 0.5517; P(free) at (1,1) = 4/29 = 0.1379, at (2,0) = 20/29 = 0.6897.

:- dynamic(action/1).          % a fact of each step (the filter's actions / facts)

cell(X, Y) := between(-1, 2, X), between(-1, 2, Y).

next_to(up, (X, Y), (X, Y1)) := Y1 is Y + 1.
next_to(down, (X, Y), (X, Y1)) := Y1 is Y - 1.
next_to(left, (X, Y), (X1, Y)) := X1 is X - 1.
next_to(right, (X, Y), (X1, Y)) := X1 is X + 1.

position:0 ~ val((0, 0)).
maze(X, Y):0 ~ val(wall) := cell(X, Y), X < 0.
maze(X, Y):0 ~ val(wall) := cell(X, Y), X >= 0, Y < 0.
maze(0, 0):0 ~ val(free).
maze(X, Y):0 ~ finite([0.2:pit, 0.8:free]) := cell(X, Y), X >= 0, Y >= 0, (X, Y) \== (0, 0).

maze(X, Y):t+1 ~ val(V) := cell(X, Y), maze(X, Y):t ~= V.

position:t+1 ~ val(Q) := action(A), position:t ~= P, next_to(A, P, Q).
position:t+1 ~ val(P) := action(null), position:t ~= P.

breezy:t+1 := position:t+1 ~= P, next_to(_, P, (X, Y)), maze(X, Y):t+1 ~= pit.

observation(breeze):t+1 ~ val(true) := breezy:t+1.
observation(breeze):t+1 ~ val(false) := \+ breezy:t+1.
