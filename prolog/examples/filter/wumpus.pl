% The wumpus maze, one filtering step (a re-statement of the original DCPF example
% dcpfwumpus.pl, dc-reference section 4, in this project's own words).
%
% An agent stands on the free cell (0,0) of a grid whose other cells are free (0.6) or a
% wall (0.4), each independently.  It can try to move up, down, left or right: the move
% succeeds 9 times out of 10 when the target cell is free and never when it is a wall;
% `null` stays put.  After each step its four sensors report the neighbouring cells as
% wall or free, each right 9 times out of 10.
%
% Conformance target: after the action null and the readings up = wall, right = free,
%   P(maze(0,1) = wall) = 0.4*0.9 / (0.4*0.9 + 0.6*0.1) = 0.857143.
% Run:  ddc filter prolog/examples/filter/wumpus.pl prolog/examples/filter/wumpus.jsonl \
%           --query 'maze(0,1):t ~= wall'

:- dynamic(action/1).          % a fact of each step (the filter's actions / facts)

cell(X, Y) := between(-2, 2, X), between(-2, 2, Y).

neighbour(up, (X, Y), (X, Y1)) := Y1 is Y + 1.
neighbour(down, (X, Y), (X, Y1)) := Y1 is Y - 1.
neighbour(left, (X, Y), (X1, Y)) := X1 is X - 1.
neighbour(right, (X, Y), (X1, Y)) := X1 is X + 1.

% Time 0: where the agent is and what the maze looks like.
position:0 ~ val((0, 0)).
maze(0, 0):0 ~ val(free).
maze(X, Y):0 ~ finite([0.6:free, 0.4:wall]) := cell(X, Y), (X, Y) \== (0, 0).

% The maze does not change.
maze(X, Y):t+1 ~ val(V) := cell(X, Y), maze(X, Y):t ~= V.

% Moving.
position:t+1 ~ finite([0.9:(TX, TY), 0.1:P]) :=
    action(A), position:t ~= P, neighbour(A, P, (TX, TY)), maze(TX, TY):t ~= free.
position:t+1 ~ val(P) :=
    action(A), position:t ~= P, neighbour(A, P, (TX, TY)), maze(TX, TY):t ~= wall.
position:t+1 ~ val(P) := action(null), position:t ~= P.

% Sensing the four neighbours of the new position.
observation(D):t+1 ~ finite([0.9:wall, 0.1:free]) :=
    position:t+1 ~= P, neighbour(D, P, (X, Y)), maze(X, Y):t+1 ~= wall.
observation(D):t+1 ~ finite([0.1:wall, 0.9:free]) :=
    position:t+1 ~= P, neighbour(D, P, (X, Y)), maze(X, Y):t+1 ~= free.
