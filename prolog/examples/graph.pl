% A probabilistic graph (the original's exampleproblog.pl), restated: each
% edge exists with probability 0.5; p/2 is reachability over existing edges,
% path/2 over a fixed graph.
e(1,2) ~ finite([0.5:true, 0.5:false]).
e(1,6) ~ finite([0.5:true, 0.5:false]).
e(2,3) ~ finite([0.5:true, 0.5:false]).
e(3,4) ~ finite([0.5:true, 0.5:false]).
e(6,5) ~ finite([0.5:true, 0.5:false]).
p(X, Y) := e(X, Y) ~= true.
p(X, Y) := e(X, Z) ~= true, p(Z, Y).
edge(1,2). edge(1,6). edge(2,3). edge(3,4). edge(6,5).
path(X, Y) :- edge(X, Y).
path(X, Y) :- edge(X, Z), path(Z, Y).
