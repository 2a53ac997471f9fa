% example1: the original DC system's README test, restated.
% Four queries: P(drawn(1) ~= 1), P(drawn(1) ~= 2), P(drawn(1) ~= 3), E[g].
nballs ~ uniform([1,2,3,4,5,6,7,8,9,10]).
drawn(_) ~ uniform(Balls) := nballs ~= N, findall(X, between(1, N, X), Balls).
g ~ gaussian(0, 0.01).
g2 ~ gaussian(M, 0.01) := g ~= M.
n2 ~ finite([0.9:1, 0.05:5, 0.05:6]).
n3 ~ poisson(4).
n4 ~ uniform([2, N]) := n2 ~= N.
n3 := n2 ~= 1, true(0.5).
n3_1 := n2 ~= 1, sample(contUniform(0, 1), X), X < 0.5.
