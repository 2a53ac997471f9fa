% Generator of the recovery test "a relational aggregate that matters"
% (tests/test_learn_recovery.py).
%
% Entities e1, e2, ... (any key: the priors have no body). Entity X has nlinks(X) neighbours,
% 1 to 5 with equal probability, its own (X = e7 has e7_1, ..., e7_N); each neighbour has two
% independent standard-normal attributes:
%     link(X, Y)               the relation (Y = X_K, K = 1..nlinks(X));
%     v(Y) ~ gaussian(0, 1)    the attribute that matters, through its mean over the neighbours;
%     w(Y) ~ gaussian(0, 1)    a distractor (no clause of y reads it).
% The target is a linear-Gaussian of the MEAN of v over X's neighbours M, weight 1.5, bias 0.2,
% variance 0.25 (sd 0.5):
%     y(X) ~ gaussian(1.5*M + 0.2, 0.25).
% Neither the number of neighbours, nor any single neighbour's v, nor the mean of w matters
% given M. evaluate/2 scores the clause of y on data with the facts of link and v (the
% derived clause of link is replaced by the data's facts).

nlinks(X) ~ uniform([1, 2, 3, 4, 5]).
link(X, Y) := nlinks(X) ~= N, between(1, N, K), atomic_list_concat([X, '_', K], Y).
v(Y) ~ gaussian(0, 1).
w(Y) ~ gaussian(0, 1).

y(X) ~ gaussian(1.5*M + 0.2, 0.25) :=
    findall(V, (link(X, Y), v(Y) ~= V), L),
    mean_list(L, M).
