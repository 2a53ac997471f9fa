% Generator of the recovery test "discrete tree of depth 2" (tests/test_learn_recovery.py).
%
% Entities e1, e2, ... (any key: the priors have no body). Three discrete features, each
% uniform over its two values and independent of the others:
%     a(X) in {p, q},  b(X) in {r, s},  c(X) in {u, v} (irrelevant: no clause of y reads it).
% The target y(X) in {t, f} depends on a and b, as the tree of depth 2
%
%     a(X) ~= p --- b(X) ~= r : P(t) = 0.9
%               \-- b(X) ~= s : P(t) = 0.6
%     a(X) ~= q --- b(X) ~= r : P(t) = 0.1
%               \-- b(X) ~= s : P(t) = 0.4
%
% Each value of a has its own subtree (a is the root: P(t | a) = 0.75 / 0.25, while b alone
% tells nothing, P(t | b) = 0.5 / 0.5, so a greedy learner must choose a first).
% evaluate/2 scores the four clauses of y on data that has the facts of a and b.

a(X) ~ finite([0.5:p, 0.5:q]).
b(X) ~ finite([0.5:r, 0.5:s]).
c(X) ~ finite([0.5:u, 0.5:v]).

y(X) ~ finite([0.9:t, 0.1:f]) := a(X) ~= p, b(X) ~= r.
y(X) ~ finite([0.6:t, 0.4:f]) := a(X) ~= p, b(X) ~= s.
y(X) ~ finite([0.1:t, 0.9:f]) := a(X) ~= q, b(X) ~= r.
y(X) ~ finite([0.4:t, 0.6:f]) := a(X) ~= q, b(X) ~= s.
